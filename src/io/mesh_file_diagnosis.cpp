// Diagnosis of mesh files CGAL refused: OFF, OBJ and ascii PLY/STL are scanned line by line for
// the first offending element; binary files get their header counts in the message.
#include "io/mesh_file_diagnosis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace lrvd {

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}


namespace {

bool parse_double(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return !token.empty() && *end == '\0';
}

// False also for an integer beyond 64 bits (which strtoll would clamp): see is_integer_text.
bool parse_long(const std::string& token, long long& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(token.c_str(), &end, 10);
  return !token.empty() && *end == '\0' && errno != ERANGE;
}

// An optional sign and decimal digits: an index, whether or not it fits in 64 bits.
bool is_integer_text(const std::string& token) {
  const std::size_t first = !token.empty() && (token[0] == '-' || token[0] == '+') ? 1 : 0;
  return token.size() > first &&
         std::all_of(token.begin() + first, token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Non-blank lines of a text file with '#' comments removed, split into tokens.
class TokenLines {
 public:
  explicit TokenLines(const std::string& path) : in_(path, std::ios::binary) {}
  bool next(std::vector<std::string>& tokens) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      line = line.substr(0, line.find('#'));
      std::istringstream words(line);
      tokens.clear();
      for (std::string w; words >> w;) tokens.push_back(w);
      if (!tokens.empty()) return true;
    }
    return false;
  }
  int line_number() const { return line_number_; }

 private:
  std::ifstream in_;
  int line_number_ = 0;
};

template <class T>
std::string non_finite(const std::string& element, const T xyz[3]) {
  if (std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2])) return "";
  return fmt::format("{} has a non-finite coordinate ({}, {}, {})", element, xyz[0], xyz[1], xyz[2]);
}

// First problem with the coordinates of `element` (e.g. "vertex 3") at tokens[first..], or "".
std::string check_coordinates(const std::vector<std::string>& tokens, std::size_t first, const std::string& element,
                              int line) {
  if (tokens.size() < first + 3) return fmt::format("{} (line {}) has fewer than 3 coordinates", element, line);
  double xyz[3];
  for (int c = 0; c < 3; ++c)
    if (!parse_double(tokens[first + c], xyz[c]))
      return fmt::format("{} (line {}): '{}' is not a number", element, line, tokens[first + c]);
  return non_finite(element, xyz);
}

// A binary OFF laid out as Geomview writes it, with a colour count (and that many floats) after
// each face's indices: CGAL's reader takes the count for the next face's size.
std::string diagnose_binary_off(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string header;
  std::getline(in, header);
  auto read_int = [&in](std::int64_t& value) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
    value = static_cast<std::int32_t>(std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3]);
    return true;
  };
  std::int64_t nv = 0, nf = 0, ne = 0;
  if (!read_int(nv) || !read_int(nf) || !read_int(ne) || nv < 0 || nf < 0) return "";
  in.seekg(12 * nv, std::ios::cur);  // x, y, z as 32-bit floats
  for (std::int64_t f = 0; f < nf; ++f) {
    std::int64_t n = 0, index = 0, colours = 0;
    if (!read_int(n) || n < 3) return "";
    for (std::int64_t k = 0; k < n; ++k)
      if (!read_int(index) || index < 0 || index >= nv) return "";
    if (!read_int(colours) || colours < 0 || colours > 4) return "";
    in.seekg(4 * colours, std::ios::cur);
  }
  if (!in || in.peek() != std::char_traits<char>::eof()) return "";
  return "is a binary OFF with a colour count after each face's indices (Geomview's layout), which CGAL's "
         "reader takes for the next face's size: save it as ASCII OFF or PLY";
}

// The line scan of an ASCII OFF file for the first thing CGAL's reader would stumble on or read
// wrong: the header, then each vertex and face, then lines after the declared faces.
class OffDiagnosis {
 public:
  explicit OffDiagnosis(const std::string& path) : path_(path), lines_(path) {}

  std::string run() {
    lines_.next(tokens_);
    const std::string magic = tokens_.empty() ? std::string() : tokens_[0];
    if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0)
      return "is not an OFF file: it does not start with 'OFF'";
    if (tokens_.size() > 1 && tokens_[1] == "BINARY") return magic == "OFF" ? diagnose_binary_off(path_) : "";
    if (std::string problem = read_counts(); !problem.empty()) return problem;
    for (long long v = 0; v < nv_; ++v)
      if (std::string problem = vertex_problem(v); !problem.empty()) return problem;
    for (long long f = 0; f < nf_; ++f)
      if (std::string problem = face_problem(f); !problem.empty()) return problem;
    // CGAL stops after the declared faces; lines after them would be dropped without a word.
    if (lines_.next(tokens_))
      return fmt::format("has more than its {} declared faces: line {} ('{}') follows them (does the header's face "
                         "count match the face lines?)",
                         nf_, lines_.line_number(), tokens_[0]);
    return "";
  }

 private:
  // CGAL reads the header's counts as tokens, across lines, and then each vertex and face from a
  // line of its own, the first from what is left of the line the counts end on.
  std::string read_counts() {
    rest_.assign(tokens_.begin() + 1, tokens_.end());
    long long counts[3];
    for (int k = 0; k < 3; ++k) {
      while (rest_.empty() && lines_.next(tokens_)) rest_ = tokens_;
      if (rest_.empty() || !parse_long(rest_.front(), counts[k]) || counts[k] < 0)
        return fmt::format(
            "has an invalid OFF header (line {}): expected the vertex, face and edge counts, e.g. "
            "'8 6 0'",
            lines_.line_number());
      rest_.erase(rest_.begin());
    }
    nv_ = counts[0], nf_ = counts[1];
    return "";
  }

  bool next_line() {
    if (rest_.empty()) return lines_.next(tokens_);
    tokens_ = std::move(rest_);
    rest_.clear();
    return true;
  }

  // A line holding more numbers than a vertex or face takes: where a file ran out early, CGAL read
  // the elements' numbers from one line as a single element (the whole file on one line, say).
  void note_if_crowded(std::size_t most) {
    if (tokens_.size() > most && crowded_line_ == 0) crowded_line_ = lines_.line_number(), crowded_numbers_ = tokens_.size();
  }
  std::string truncated(const std::string& usual) const {
    if (crowded_line_ == 0) return usual;
    return fmt::format("has several vertices or faces on one line (line {} holds {} numbers), but CGAL's OFF reader "
                       "takes each from a line of its own, so the file ends too early for the header's {} vertices "
                       "and {} faces: put each vertex and face on a line of its own",
                       crowded_line_, crowded_numbers_, nv_, nf_);
  }

  std::string vertex_problem(long long v) {
    if (!next_line())
      return truncated(fmt::format(
          "is truncated: the header declares {} vertices and {} faces, but the file ends after {} "
          "vertices",
          nv_, nf_, v));
    if (std::string problem = check_coordinates(tokens_, 0, fmt::format("vertex {}", v), lines_.line_number());
        !problem.empty())
      return problem;
    note_if_crowded(10);  // x y z, a normal and an RGBA colour at most
    return "";
  }

  std::string face_problem(long long f) {
    if (!next_line())
      return truncated(fmt::format("is truncated: the header declares {} faces, but the file ends after {}", nf_, f));
    const int line = lines_.line_number();
    long long n = 0;
    if (!parse_long(tokens_[0], n) || n < 0)
      return fmt::format("face {} (line {}): '{}' is not a vertex count", f, line, tokens_[0]);
    if (n < 3)
      return fmt::format("face {} (line {}) has {} vertices; a face needs at least 3 (does the header's vertex count, {}, "
                         "match the vertex lines?)",
                         f, line, n, nv_);
    if (static_cast<long long>(tokens_.size()) < n + 1)
      return fmt::format("face {} (line {}) lists {} of its {} vertex indices", f, line, tokens_.size() - 1, n);
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!parse_long(tokens_[k], index))
        return is_integer_text(tokens_[k])
                   ? fmt::format("face {} has vertex index {} out of range [0, {})", f, tokens_[k], nv_)
                   : fmt::format("face {} (line {}): '{}' is not a vertex index", f, line, tokens_[k]);
      if (index < 0 || index >= nv_) return fmt::format("face {} has vertex index {} out of range [0, {})", f, index, nv_);
    }
    note_if_crowded(static_cast<std::size_t>(n + 5));
    // A face may end with a colour (an index or three or four numbers), nothing else.
    for (std::size_t k = n + 1; k < tokens_.size(); ++k) {
      double value = 0;
      if (!parse_double(tokens_[k], value))
        return fmt::format("face {} (line {}): '{}' after its {} vertex indices is not a number (only a colour may "
                           "follow them)",
                           f, line, tokens_[k], n);
    }
    return "";
  }

  const std::string path_;
  TokenLines lines_;
  std::vector<std::string> tokens_, rest_;
  long long nv_ = 0, nf_ = 0;
  int crowded_line_ = 0;
  std::size_t crowded_numbers_ = 0;
};

std::string diagnose_off(const std::string& path) { return OffDiagnosis(path).run(); }

// The statements CGAL 5.5's OBJ reader accepts and ignores; any other one makes it fail.
const char* const obj_statements_cgal_skips[] = {
    "vt",     "vn",       "vp",     "bevel",      "lod",       "ctech",  "c_interp", "usemap", "usemtl",
    "stech",  "d_interp", "mtllib", "shadow_obj", "trace_obj", "o",      "g",        "s",      "p",
    "cstype", "deg",      "step",   "bmat",       "con",       "curv",   "curv2",    "surf",   "parm",
    "trim",   "hole",     "scrv",   "sp",         "end",       "surf_1", "q0_1",     "q1_1",   "curv2d_1",
    "surf_2", "q0_2",     "q1_2",   "curv2d_2",   "bsp",       "bzp",    "cdc",      "cdp",    "res"};

std::string diagnose_obj(const std::string& path) {
  long long nv = 0, nf = 0;
  std::vector<std::string> tokens;
  for (TokenLines lines(path); lines.next(tokens);) {
    const std::string& key = tokens[0];
    if (key == "v") {
      if (std::string problem = check_coordinates(tokens, 1, fmt::format("vertex {}", nv), lines.line_number());
          !problem.empty())
        return problem;
      ++nv;
    } else if (key == "f") {
      ++nf;
    } else if (std::find(std::begin(obj_statements_cgal_skips), std::end(obj_statements_cgal_skips), key) ==
               std::end(obj_statements_cgal_skips)) {
      return fmt::format("line {}: the OBJ statement '{}' is not supported (CGAL reads v and f)", lines.line_number(),
                         key);
    }
  }
  if (nf == 0)
    return nv == 0 ? "has no vertices and no faces" : fmt::format("has {} vertices but no faces (a point cloud?)", nv);
  // Second pass: indices against the final vertex count (positive) or the count so far (negative).
  long long seen = 0, f = 0;
  for (TokenLines lines(path); lines.next(tokens);) {
    if (tokens[0] == "v") ++seen;
    if (tokens[0] != "f") continue;
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      long long index = 0;
      const std::string text = tokens[k].substr(0, tokens[k].find('/'));
      const bool parsed = parse_long(text, index);
      if (!parsed && is_integer_text(text))  // beyond 64 bits: out of range either way
        return fmt::format("face {} (line {}) refers to vertex {}, but the file has {} vertices", f,
                           lines.line_number(), text, text[0] == '-' ? seen : nv);
      if (!parsed || index == 0)
        return fmt::format("face {} (line {}): '{}' is not a vertex index", f, lines.line_number(), tokens[k]);
      if (index > nv || index < -seen)
        return fmt::format("face {} (line {}) refers to vertex {}, but the file has {} vertices", f,
                           lines.line_number(), index, index > 0 ? nv : seen);
    }
    ++f;
  }
  return "";
}

// A PLY header as far as the diagnosis needs it.
struct PlyHeader {
  bool is_ply = false, ended = false;
  std::string format;
  std::vector<std::pair<std::string, long long>> elements;
  std::vector<std::string> vertex_properties;
};

PlyHeader read_ply_header(std::istream& in, int& line_number) {
  PlyHeader h;
  std::string line;
  line_number = 1;
  if (!std::getline(in, line) || line.substr(0, 3) != "ply") return h;
  h.is_ply = true;
  while (!h.ended && std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    std::string key, name;
    words >> key;
    if (key == "format") {
      words >> h.format;
    } else if (key == "element") {
      long long count = -1;
      words >> name >> count;
      h.elements.emplace_back(name, count);
    } else if (key == "property" && !h.elements.empty() && h.elements.back().first == "vertex") {
      words >> name >> name;
      h.vertex_properties.push_back(name);
    }
    h.ended = key == "end_header";
  }
  return h;
}

// PLY: the header, then (ascii only) the vertex coordinates and the number of body lines.
std::string diagnose_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  int line_number = 1;
  const PlyHeader header = read_ply_header(in, line_number);
  if (!header.is_ply) return "is not a PLY file: it does not start with 'ply'";
  if (!header.ended) return "has an invalid PLY header: no 'end_header' line";
  const std::string& format = header.format;
  const auto& elements = header.elements;
  const auto& vertex_properties = header.vertex_properties;
  long long nv = 0, nf = 0;
  // The header's counts are any long long: their sums, and a line number against them, are taken
  // in 128 bits, where none overflows.
  __int128 after_vertices = 0;
  for (const auto& [name, count] : elements) {
    if (name == "vertex") nv = count;
    if (name == "face") nf = count;
    if (name != "vertex") after_vertices += count;
  }
  const std::string generic = fmt::format(
      "cannot be parsed as {} PLY: the body is truncated or does not match the header ({} vertices, {} faces)", format,
      nv, nf);
  const auto x = std::find(vertex_properties.begin(), vertex_properties.end(), "x");
  if (format != "ascii" || elements.empty() || elements[0].first != "vertex" || vertex_properties.end() - x < 3 ||
      x[1] != "y" || x[2] != "z")
    return generic;
  std::vector<std::string> tokens;
  long long body_lines = 0;
  const bool faces_follow = elements.size() > 1 && elements[1].first == "face";
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    tokens.clear();
    for (std::string w; words >> w;) tokens.push_back(w);
    if (tokens.empty()) continue;
    if (body_lines < nv) {
      const std::size_t first = static_cast<std::size_t>(x - vertex_properties.begin());
      if (std::string problem = check_coordinates(tokens, first, fmt::format("vertex {}", body_lines), line_number);
          !problem.empty())
        return problem;
    } else if (faces_follow && body_lines < static_cast<__int128>(nv) + nf) {
      // A face: its vertex count, then that many indices into the vertices (CGAL reads them as
      // ints, and refuses the body at one it cannot).
      const long long f = body_lines - nv;
      long long n = 0;
      if (parse_long(tokens[0], n) && n >= 0 && static_cast<long long>(tokens.size()) > n)
        for (long long k = 1; k <= n; ++k) {
          long long index = 0;
          if (is_integer_text(tokens[k]) && (!parse_long(tokens[k], index) || index < 0 || index >= nv))
            return fmt::format("face {} (line {}) has vertex index {} out of range [0, {})", f, line_number, tokens[k],
                               nv);
        }
    }
    ++body_lines;
  }
  if (body_lines < nv)
    return fmt::format(
        "is truncated: the header declares {} vertices and {} faces, but the file ends after {} "
        "vertices",
        nv, nf, body_lines);
  if (body_lines < nv + after_vertices)  // in 128 bits
    return fmt::format(
        "is truncated: the header declares {} vertices and {} faces, but the body has only {} "
        "lines after the vertices",
        nv, nf, body_lines - nv);
  return generic;
}

std::string diagnose_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string first;
  in >> first;
  if (first != "solid") {
    in.clear();
    in.seekg(0, std::ios::end);
    const long long size = in.tellg();
    unsigned char count[4] = {};
    in.seekg(80);
    if (size < 84 || !in.read(reinterpret_cast<char*>(count), 4))
      return fmt::format("is truncated or malformed as binary STL: it has {} bytes, not 84 + 50 per facet", size);
    const std::uint64_t facets = count[0] | count[1] << 8 | count[2] << 16 | std::uint64_t(count[3]) << 24;
    return fmt::format("is truncated or malformed as binary STL: it has {} bytes, not the 84 + 50 x {} = {} its "
                       "header's count of {} facets takes",
                       size, facets, 84 + 50 * facets, facets);
  }
  TokenLines lines(path);
  std::vector<std::string> tokens;
  long long facet = -1;
  while (lines.next(tokens)) {
    if (tokens[0] == "facet") ++facet;
    if (tokens[0] == "endsolid") return "";
    if (tokens[0] != "vertex") continue;
    if (std::string problem = check_coordinates(tokens, 1, fmt::format("facet {}", facet), lines.line_number());
        !problem.empty())
      return problem;
  }
  return fmt::format("is truncated: the ascii STL ends after {} facets without 'endsolid'", facet + 1);
}

}  // namespace

std::string diagnose_unreadable_mesh_file(const std::string& path, MeshFileFormat format) {
  // Editors on Windows often start a text file with one; CGAL's readers take it for data.
  char bom[3] = {};
  if (std::ifstream(path, std::ios::binary).read(bom, 3) && bom[0] == '\xef' && bom[1] == '\xbb' && bom[2] == '\xbf')
    return "starts with a UTF-8 byte-order mark, which CGAL's reader does not accept: save the file without it";
  std::string reason;
  if (format == MeshFileFormat::Off) reason = diagnose_off(path);
  if (format == MeshFileFormat::Obj) reason = diagnose_obj(path);
  if (format == MeshFileFormat::Ply) reason = diagnose_ply(path);
  if (format == MeshFileFormat::Stl) reason = diagnose_stl(path);
  if (reason.empty()) {
    static const char* names[] = {"OFF", "OBJ", "PLY", "STL"};
    reason = fmt::format("cannot be parsed as {} (CGAL's reader refused it)", names[int(format)]);
  }
  return reason;
}

std::string find_misread_line(const std::string& path, MeshFileFormat format) {
  if (format == MeshFileFormat::Off) return diagnose_off(path);
  if (format == MeshFileFormat::Obj) return diagnose_obj(path);
  return "";
}

std::string find_missing_ply_coordinates(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  int line_number = 0;
  const PlyHeader header = read_ply_header(in, line_number);
  if (!header.is_ply || !header.ended) return "";
  std::string missing, present;
  for (const char* c : {"x", "y", "z"})
    if (std::find(header.vertex_properties.begin(), header.vertex_properties.end(), c) == header.vertex_properties.end())
      missing += missing.empty() ? c : std::string(", ") + c;
  if (missing.empty()) return "";
  for (const std::string& name : header.vertex_properties) present += (present.empty() ? "" : ", ") + name;
  return fmt::format("its vertex element has no {} propert{} (it has: {})", missing, missing.size() == 1 ? "y" : "ies",
                     present.empty() ? "none" : present);
}

std::string find_non_finite_binary_stl_coordinate(const std::string& path) {
  const std::string bytes = [&] {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }();
  if (bytes.size() < 84) return "";
  std::uint32_t facets = 0;
  for (int i = 0; i < 4; ++i)
    facets |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[80 + i])) << (8 * i);
  // Not binary (or truncated); a few bytes of padding after the facets are let through, as by read_mesh.
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(facets);
  if (bytes.size() < expected || bytes.size() >= expected + 50) return "";
  for (std::uint32_t f = 0; f < facets; ++f)
    for (int corner = 1; corner <= 3; ++corner) {  // record: normal, 3 corners, attribute
      float xyz[3];
      std::memcpy(xyz, bytes.data() + 84 + 50 * std::size_t(f) + 12 * corner, sizeof xyz);  // little-endian host
      if (std::string problem = non_finite(fmt::format("facet {}", f), xyz); !problem.empty()) return problem;
    }
  return "";
}

}  // namespace lrvd
