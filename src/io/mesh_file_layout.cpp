// Header counts against file sizes, PLY lists against the bytes left, and what follows the last
// declared element: a walk over the file's structure (header tokens, PLY list counts), no data.
#include "io/mesh_file_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace lrvd {

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool parse_count(const std::string& token, long long& value) {
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(token.c_str(), &end, 10);
  return !token.empty() && *end == '\0' && errno != ERANGE && value >= 0;
}

// "vertices", "faces", or "'edge' elements": how messages name an element's items.
std::string items(const std::string& element) {
  if (element == "vertex" || element == "vertices") return "vertices";
  if (element == "face" || element == "faces") return "faces";
  return "'" + element + "' elements";
}

std::string too_short(const std::string& declared, double need, std::size_t header, std::size_t size) {
  return fmt::format("is too short for its header: it declares {}, which take at least {:.0f} bytes after its "
                     "{}-byte header, but the file has only {} bytes (is the file truncated or a count wrong?)",
                     declared, need, header, size);
}

// ---------------------------------------------------------------------------------------------
// OFF

// The header's tokens as CGAL's reader takes them: separated by any whitespace, line breaks
// included, '#' starting a comment to the end of its line.
bool next_header_token(std::istream& in, std::string& token) {
  token.clear();
  for (int c; (c = in.get()) != EOF;) {
    if (c == '#') {
      while ((c = in.get()) != EOF && c != '\n') {
      }
      continue;
    }
    if (std::isspace(c)) continue;
    token.push_back(static_cast<char>(c));
    while ((c = in.peek()) != EOF && !std::isspace(c) && c != '#') token.push_back(static_cast<char>(in.get()));
    return true;
  }
  return false;
}

// The header's third count (edges), which OFF readers ignore but CGAL doubles in an int: from 2^30
// on, that overflows.
constexpr long long kMostOffEdges = 1LL << 30;

std::string edge_count_problem(const std::string& count) {
  return fmt::format("has an invalid OFF header: its edge count {} is out of range (it is unused; write 0)", count);
}

std::int64_t big_endian_int32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
  return static_cast<std::int32_t>(v);
}

std::string binary_off_layout(const std::string& path, const std::string& magic) {
  if (magic != "OFF") return "";  // the plain layout; CGAL's binary variants are not walked
  const std::string bytes = file_bytes(path);
  std::size_t pos = bytes.find('\n');
  if (pos == std::string::npos || bytes.size() < pos + 1 + 12) return "";
  pos += 1;
  const std::int64_t nv = big_endian_int32(bytes, pos), nf = big_endian_int32(bytes, pos + 4);
  const std::int64_t edges = big_endian_int32(bytes, pos + 8);
  if (edges >= kMostOffEdges || edges <= -kMostOffEdges) return edge_count_problem(std::to_string(edges));
  if (nv < 0 || nf < 0) return "";
  pos += 12;
  const double need = 12.0 * nv + 16.0 * nf;  // 3 floats a vertex; a count and 3 indices a triangle
  if (need > static_cast<double>(bytes.size() - pos))
    return too_short(fmt::format("{} vertices and {} faces", nv, nf), need, pos, bytes.size());
  // Each face's vertex count, which CGAL's reader allocates before reading the indices.
  pos += 12 * static_cast<std::size_t>(nv);
  for (std::int64_t f = 0; f < nf; ++f) {
    if (bytes.size() < pos + 4) return "";
    const std::int64_t n = big_endian_int32(bytes, pos);
    pos += 4;
    if (n < 0) return "";
    const std::size_t left = bytes.size() - pos;
    if (static_cast<std::uint64_t>(n) > left / 4) {
      // Geomview's layout (a colour count after each face) misaligns this walk: say that instead.
      const std::string layout = diagnose_unreadable_mesh_file(path, MeshFileFormat::Off);
      if (layout.find("colour count") != std::string::npos) return layout;
      return fmt::format("face {} declares {} vertices, more than the {} bytes left in the file hold", f, n, left);
    }
    pos += 4 * static_cast<std::size_t>(n);
  }
  return "";
}

std::string off_layout(const std::string& path) {
  const std::size_t size = std::filesystem::file_size(path);
  std::ifstream in(path, std::ios::binary);
  std::string magic, token;
  if (!next_header_token(in, magic) || magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0) return "";
  const std::string prefix = magic.substr(0, magic.size() - 3);
  {
    std::string first_line;
    std::ifstream head(path, std::ios::binary);
    std::getline(head, first_line);
    std::istringstream words(first_line);
    std::string word;
    words >> word >> word;
    if (word == "BINARY") return binary_off_layout(path, magic);
  }
  double vertex_bytes = 6;  // "\n0 0 0": three numbers and the separators before them
  if (prefix.find('n') != std::string::npos) {  // nOFF: the dimension comes first
    long long dimension = 0;
    if (!next_header_token(in, token) || !parse_count(token, dimension)) return "";
    vertex_bytes = 2.0 * std::max(1LL, dimension);
  }
  long long counts[3];
  for (int i = 0; i < 3; ++i) {
    if (!next_header_token(in, token)) return "";
    long long edges = 0;
    if (i == 2 && parse_count(token.front() == '-' ? token.substr(1) : token, edges) && edges >= kMostOffEdges)
      return edge_count_problem(token);
    if (!parse_count(token, counts[i])) return "";
  }
  const long long nv = counts[0], nf = counts[1];
  const std::streamoff header = in.tellg();
  if (header < 0) return "";
  // A triangle needs "\n3 0 1 2", 8 bytes; a face with fewer vertices is refused anyway.
  const double need = vertex_bytes * nv + 8.0 * nf;
  if (!(need > static_cast<double>(size) - static_cast<double>(header))) return "";
  // The line scan, which stops where the file does, says where that is.
  const std::string scanned = diagnose_unreadable_mesh_file(path, MeshFileFormat::Off);
  if (scanned.rfind("is truncated", 0) == 0 || scanned.rfind("has several", 0) == 0)
    return fmt::format("{}; its {} bytes could not hold them", scanned, size);
  return too_short(fmt::format("{} vertices and {} faces", nv, nf), need, static_cast<std::size_t>(header), size);
}

// ---------------------------------------------------------------------------------------------
// PLY

struct PlyProperty {
  std::string name;
  bool list = false;
  int size = 0;        // a scalar's bytes, or a list item's
  int count_size = 0;  // a list's count bytes
  bool signed_count = false;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

// Bytes of a PLY scalar type (both spellings), 0 for an unknown one.
int ply_type_size(const std::string& type, bool* is_signed = nullptr) {
  static const struct {
    const char *name, *alias;
    int size;
    bool is_signed;
  } types[] = {{"char", "int8", 1, true},     {"uchar", "uint8", 1, false}, {"short", "int16", 2, true},
               {"ushort", "uint16", 2, false}, {"int", "int32", 4, true},    {"uint", "uint32", 4, false},
               {"float", "float32", 4, true},  {"double", "float64", 8, true}};
  for (const auto& t : types)
    if (type == t.name || type == t.alias) {
      if (is_signed) *is_signed = t.is_signed;
      return t.size;
    }
  return 0;
}

bool is_face_indices(const PlyElement& element, const PlyProperty& property) {
  return (element.name == "face" || element.name == "faces") && property.list &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

// The fewest bytes one item of `element` takes: a list its count alone, except a face's indices,
// which need three (lrvd refuses a face with fewer anyway).
double min_item_bytes(const PlyElement& element, bool ascii) {
  double bytes = 0;
  for (const PlyProperty& p : element.properties) {
    if (ascii)
      bytes += 2 + (is_face_indices(element, p) ? 6 : 0);  // a number and a separator each
    else
      bytes += p.list ? p.count_size + (is_face_indices(element, p) ? 3 * p.size : 0) : p.size;
  }
  return bytes;
}

std::string describe_counts(const std::vector<PlyElement>& elements) {
  std::string text;
  for (std::size_t e = 0; e < elements.size(); ++e)
    text += fmt::format("{}{} {}", e == 0 ? "" : e + 1 == elements.size() ? " and " : ", ", elements[e].count,
                        items(elements[e].name));
  return text;
}

std::string extra_after(const PlyElement& last, const std::string& what) {
  return fmt::format("has more than its {} declared {}: {} (does the header's count match the body?)", last.count,
                     items(last.name), what);
}

std::uint64_t read_unsigned(const std::string& bytes, std::size_t at, int size, bool big_endian) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) {
    const std::uint64_t byte = static_cast<unsigned char>(bytes[at + (big_endian ? i : size - 1 - i)]);
    v = v << 8 | byte;
  }
  return v;
}

std::string binary_ply_body(const std::string& bytes, std::size_t pos, const std::vector<PlyElement>& elements,
                            bool big_endian) {
  const std::size_t n = bytes.size();
  for (const PlyElement& element : elements) {
    const bool fixed = std::none_of(element.properties.begin(), element.properties.end(),
                                    [](const PlyProperty& p) { return p.list; });
    if (fixed) {
      std::size_t item = 0;
      for (const PlyProperty& p : element.properties) item += p.size;
      if (item == 0) continue;
      if (static_cast<std::uint64_t>(element.count) > (n - pos) / item) return "";  // truncated: CGAL says so
      pos += item * static_cast<std::size_t>(element.count);
      continue;
    }
    for (long long j = 0; j < element.count; ++j)
      for (const PlyProperty& p : element.properties) {
        if (!p.list) {
          if (n - pos < static_cast<std::size_t>(p.size)) return "";
          pos += p.size;
          continue;
        }
        if (n - pos < static_cast<std::size_t>(p.count_size)) return "";
        std::uint64_t count = read_unsigned(bytes, pos, p.count_size, big_endian);
        if (p.signed_count && count >> (8 * p.count_size - 1)) return "";  // negative: CGAL refuses it
        pos += p.count_size;
        if (count > (n - pos) / p.size)
          return fmt::format("{} {}'s {} list declares {} entries, more than the {} bytes left in the file hold",
                             element.name, j, p.name, count, n - pos);
        pos += p.size * static_cast<std::size_t>(count);
      }
  }
  const PlyElement& last = elements.back();
  const double room = std::max(1.0, min_item_bytes(last, false));
  if (static_cast<double>(n - pos) >= room)
    return extra_after(last, fmt::format("{} bytes follow them, room for another", n - pos));
  return "";
}

std::string ascii_ply_body(const std::string& bytes, std::size_t pos, const std::vector<PlyElement>& elements) {
  const std::size_t n = bytes.size();
  auto token = [&](std::size_t& begin, std::size_t& end) {
    while (pos < n && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    begin = pos;
    while (pos < n && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    end = pos;
    return end > begin;
  };
  std::size_t begin = 0, end = 0;
  for (const PlyElement& element : elements)
    for (long long j = 0; j < element.count; ++j)
      for (const PlyProperty& p : element.properties) {
        if (!token(begin, end)) return "";  // truncated: CGAL refuses it and the diagnosis says so
        if (!p.list) continue;
        long long count = 0;
        if (!parse_count(bytes.substr(begin, end - begin), count)) return "";
        if (static_cast<std::uint64_t>(count) > (n - pos) / 2 + 1)
          return fmt::format("{} {}'s {} list declares {} entries, more than the {} bytes left in the file hold",
                             element.name, j, p.name, count, n - pos);
        for (long long k = 0; k < count; ++k)
          if (!token(begin, end)) return "";
      }
  if (!token(begin, end)) return "";
  const long long line = 1 + std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(begin), '\n');
  std::size_t line_end = bytes.find_first_of("\r\n", begin);
  if (line_end == std::string::npos) line_end = n;
  return extra_after(elements.back(),
                     fmt::format("line {} ('{}') follows them", line,
                                 bytes.substr(begin, std::min<std::size_t>(line_end - begin, 40))));
}

std::string ply_layout(const std::string& path) {
  const std::string bytes = file_bytes(path);
  std::size_t pos = 0;
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  for (int line_number = 1; !ended && pos < bytes.size(); ++line_number) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos) eol = bytes.size();  // the last line (no end_header: the diagnosis says so)
    std::istringstream words(bytes.substr(pos, eol - pos));
    pos = eol + 1;
    std::string key;
    words >> key;
    if (line_number == 1) {
      if (key != "ply") return "";
      continue;
    }
    if (key == "format") {
      words >> format;
    } else if (key == "element") {
      std::string name, count;
      words >> name >> count;
      elements.push_back({name, 0, {}});
      if (!parse_count(count, elements.back().count)) return "";
    } else if (key == "property") {
      if (elements.empty())  // CGAL's reader would add it to the last of no elements
        return fmt::format("has an invalid PLY header: line {} declares a property before any 'element' line",
                           line_number);
      std::string type, name;
      words >> type;
      PlyProperty p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.list = true;
        p.count_size = ply_type_size(count_type, &p.signed_count);
        p.size = ply_type_size(item_type);
      } else {
        words >> p.name;
        p.size = ply_type_size(type);
      }
      if (p.size == 0 || (p.list && p.count_size == 0)) return "";  // a type CGAL does not know
      elements.back().properties.push_back(p);
    } else if (key == "end_header") {
      ended = true;
    }
  }
  if (!ended || elements.empty()) return "";
  const bool ascii = format == "ascii";
  if (!ascii && format != "binary_little_endian" && format != "binary_big_endian") return "";
  double need = 0;
  for (const PlyElement& element : elements) need += element.count * min_item_bytes(element, ascii);
  if (need - (ascii ? 1 : 0) > static_cast<double>(bytes.size() - pos))
    return too_short(describe_counts(elements), need, pos, bytes.size());
  return ascii ? ascii_ply_body(bytes, pos, elements)
               : binary_ply_body(bytes, pos, elements, format == "binary_big_endian");
}

// ---------------------------------------------------------------------------------------------
// STL

std::string stl_layout(const std::string& path) {
  const std::size_t size = std::filesystem::file_size(path);
  if (size >= 84) return "";
  std::string head = file_bytes(path);
  head.erase(head.begin(), std::find_if(head.begin(), head.end(), [](char c) { return !std::isspace(static_cast<unsigned char>(c)); }));
  if (head.rfind("solid", 0) == 0) return "";
  return fmt::format("is too short to be an STL file ({} bytes): it holds neither a binary STL's 84-byte header "
                     "nor an ascii STL's 'solid'",
                     size);
}

}  // namespace

std::string find_layout_problem(const std::string& path, MeshFileFormat format) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return "";  // a pipe or a device: not measured
  switch (format) {
    case MeshFileFormat::Off:
      return off_layout(path);
    case MeshFileFormat::Ply:
      return ply_layout(path);
    case MeshFileFormat::Stl:
      return stl_layout(path);
    case MeshFileFormat::Obj:
      return "";  // CGAL's OBJ reader grows its vectors as it reads
  }
  return "";
}

std::string find_extra_binary_stl_facets(const std::string& path, std::size_t facets_read) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[84];
  if (!in.read(reinterpret_cast<char*>(header), 84)) return "";
  std::uint64_t declared = 0;
  for (int i = 3; i >= 0; --i) declared = declared << 8 | header[80 + i];
  if (declared != facets_read) return "";  // read as ascii
  const std::uint64_t size = std::filesystem::file_size(path), expected = 84 + 50 * declared;
  if (size < expected + 50) return "";  // a few bytes of padding are tolerated
  return fmt::format("is a binary STL whose header declares {} facets (84 + 50 x {} = {} bytes), but it has {} bytes, "
                     "room for {} more facet{} (does the header's facet count match the facets?)",
                     declared, declared, expected, size, (size - expected) / 50, (size - expected) / 50 == 1 ? "" : "s");
}

}  // namespace lrvd
