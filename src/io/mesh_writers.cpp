// Mesh files out: OFF / OBJ (ascii, %.17g so doubles round-trip) and binary PLY, and the
// Voronoi-cell polygons with a cell label and colour per face.
#include "io/mesh_writers.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/error.h"
#include "io/mesh_file_diagnosis.h"

namespace lrvd {

namespace {

// The part files being written, in a table a signal handler can read (remove_part_files_on_signals).
// Files are written one at a time (by one thread); more than four at once, or paths too long for a
// slot, are written as well, only not removed on a signal.
constexpr int kPartSlots = 4;
constexpr std::size_t kPartPathMax = 4096;
char part_paths[kPartSlots][kPartPathMax];
volatile std::sig_atomic_t part_in_use[kPartSlots];

int register_part(const std::string& path) {
  if (path.size() >= kPartPathMax) return -1;
  for (int k = 0; k < kPartSlots; ++k)
    if (!part_in_use[k]) {
      std::memcpy(part_paths[k], path.c_str(), path.size() + 1);
      std::atomic_signal_fence(std::memory_order_seq_cst);  // the path is in place before the flag
      part_in_use[k] = 1;
      return k;
    }
  return -1;
}

void unregister_part(int slot) {
  if (slot >= 0) part_in_use[slot] = 0;
}

extern "C" void remove_parts_and_reraise(int signal_number) {
  for (int k = 0; k < kPartSlots; ++k)
    if (part_in_use[k]) ::unlink(part_paths[k]);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

[[noreturn]] void fail(const std::string& path, const std::string& reason) { throw InputError(path + ": " + reason); }

// A file written whole or not at all: the data go to `file`.lrvd-part beside it, which replaces
// `file` when closed, so a run stopped while writing (or a full disk) leaves the old file or none,
// never a truncated one. `file` is `path`, or the file a symbolic link there leads to (the link
// stays). A device or a pipe that is there already (-o /dev/null) is written in place.
class OutputFile {
 public:
  explicit OutputFile(const std::string& path) : path_(path), file_path_(written_file(path)) {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::file_status status = fs::symlink_status(file_path_, error);
    in_place_ = fs::exists(status) && !fs::is_regular_file(status);
    part_ = in_place_ ? path : file_path_ + ".lrvd-part";
    // A part file left by an earlier run goes first; made afresh and exclusively ("x"), the part
    // file is never a link planted there that would carry the data to another file (an input).
    if (!in_place_) std::remove(part_.c_str());
    file_ = std::fopen(part_.c_str(), in_place_ ? "wb" : "wbx");
    if (!file_) fail(path, fmt::format("cannot be opened for writing ({})", std::strerror(errno)));
    if (in_place_) return;
    slot_ = register_part(part_);
    // The file it replaces keeps its permissions (a private 0600 file does not become 0644).
    struct stat old {};
    if (::stat(file_path_.c_str(), &old) == 0 && S_ISREG(old.st_mode)) ::fchmod(::fileno(file_), old.st_mode & 07777);
  }
  ~OutputFile() {
    if (!file_) return;
    std::fclose(file_);
    if (!in_place_) std::remove(part_.c_str());
    unregister_part(slot_);
  }
  void write(const char* data, std::size_t size) {
    if (std::fwrite(data, 1, size, file_) != size) throw WriteError(path_ + ": write failed");
  }
  void write(const fmt::memory_buffer& buffer) { write(buffer.data(), buffer.size()); }
  void close() {
    const bool ok = std::fclose(file_) == 0;
    file_ = nullptr;
    const bool replaced = ok && (in_place_ || std::rename(part_.c_str(), file_path_.c_str()) == 0);
    if (!replaced) {
      // errno is the rename's, read before the removal sets its own.
      const std::string reason = ok ? fmt::format("cannot replace it ({})", std::strerror(errno)) : "write failed";
      if (!in_place_) std::remove(part_.c_str());
      unregister_part(slot_);
      throw WriteError(path_ + ": " + reason);
    }
    unregister_part(slot_);
  }

 private:
  std::string path_, file_path_, part_;
  int slot_ = -1;  // in the table of part files being written
  bool in_place_ = false;
  std::FILE* file_ = nullptr;
};

void put_le(fmt::memory_buffer& out, uint64_t bits, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}
void put_double(fmt::memory_buffer& out, double value) {
  uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  put_le(out, bits, 8);
}
void put_int(fmt::memory_buffer& out, int value) { put_le(out, static_cast<uint32_t>(value), 4); }

template <class Face>
void check_indices(const Face& face, std::size_t vertex_count, std::size_t f) {
  for (int v : face)
    if (v < 0 || static_cast<std::size_t>(v) >= vertex_count)
      throw std::invalid_argument(fmt::format("face {} has vertex index {} out of range [0, {})", f, v, vertex_count));
}

}  // namespace

void remove_part_files_on_signals() {
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    // A signal the process was started to ignore (a job under nohup) stays ignored.
    if (::sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_parts_and_reraise;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

std::string written_file(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code error;
  for (int hops = 0; hops < 40 && fs::is_symlink(p, error); ++hops) {
    const fs::path target = fs::read_symlink(p, error);
    if (error) break;
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return p.string();
}

void write_text_file(const std::string& path, std::string_view text) {
  OutputFile file(path);
  file.write(text.data(), text.size());
  file.close();
}

const std::vector<std::string> kMeshWriteExtensions = {".off", ".obj", ".ply"};

void write_mesh(const std::string& path, const std::vector<Vec3>& positions,
                const std::vector<std::array<int, 3>>& triangles) {
  const std::string ext = lowercase_extension(path);
  if (std::find(kMeshWriteExtensions.begin(), kMeshWriteExtensions.end(), ext) == kMeshWriteExtensions.end())
    fail(path, fmt::format("cannot write meshes with extension '{}'; use .off, .obj or .ply", ext));
  for (std::size_t t = 0; t < triangles.size(); ++t) check_indices(triangles[t], positions.size(), t);
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!std::isfinite(positions[v].x) || !std::isfinite(positions[v].y) || !std::isfinite(positions[v].z))
      throw std::invalid_argument(fmt::format("vertex {} of the mesh for {} is at ({}, {}, {}): not a point", v, path,
                                              positions[v].x, positions[v].y, positions[v].z));
  OutputFile file(path);
  fmt::memory_buffer out;
  if (ext == ".off") {
    fmt::format_to(std::back_inserter(out), "OFF\n{} {} 0\n", positions.size(), triangles.size());
    for (const Vec3& p : positions) fmt::format_to(std::back_inserter(out), "{:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
    for (const auto& t : triangles) fmt::format_to(std::back_inserter(out), "3 {} {} {}\n", t[0], t[1], t[2]);
  } else if (ext == ".obj") {
    fmt::format_to(std::back_inserter(out), "# written by lrvd\n");
    for (const Vec3& p : positions)
      fmt::format_to(std::back_inserter(out), "v {:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
    for (const auto& t : triangles)
      fmt::format_to(std::back_inserter(out), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  } else {
    fmt::format_to(std::back_inserter(out),
                   "ply\nformat binary_little_endian 1.0\ncomment written by lrvd\nelement vertex {}\n"
                   "property double x\nproperty double y\nproperty double z\nelement face {}\n"
                   "property list uchar int vertex_indices\nend_header\n",
                   positions.size(), triangles.size());
    for (const Vec3& p : positions)
      for (int c = 0; c < 3; ++c) put_double(out, p[c]);
    for (const auto& t : triangles) {
      out.push_back(3);
      for (int v : t) put_int(out, v);
    }
  }
  file.write(out);
  file.close();
}

void write_mesh(const std::string& path, const SurfaceMesh& mesh) {
  write_mesh(path, mesh.positions(), mesh.triangles());
}

void write_cells_ply(const std::string& path, const PolygonMesh& mesh) {
  const std::size_t nf = mesh.faces.size();
  const bool cells = !mesh.face_cell.empty(), colors = !mesh.face_color.empty();
  if ((cells && mesh.face_cell.size() != nf) || (colors && mesh.face_color.size() != nf))
    throw std::invalid_argument("write_cells_ply: face_cell and face_color need 0 or one entry per face");
  for (std::size_t f = 0; f < nf; ++f) {
    if (mesh.faces[f].size() > 255) throw std::invalid_argument(fmt::format("face {} has more than 255 vertices", f));
    check_indices(mesh.faces[f], mesh.positions.size(), f);
  }
  OutputFile file(path);
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "ply\nformat binary_little_endian 1.0\ncomment Voronoi cells written by lrvd\nelement vertex {}\n"
                 "property double x\nproperty double y\nproperty double z\nelement face {}\n"
                 "property list uchar int vertex_indices\n{}{}end_header\n",
                 mesh.positions.size(), nf, cells ? "property int cell\n" : "",
                 colors ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "");
  for (const Vec3& p : mesh.positions)
    for (int c = 0; c < 3; ++c) put_double(out, p[c]);
  for (std::size_t f = 0; f < nf; ++f) {
    out.push_back(static_cast<char>(mesh.faces[f].size()));
    for (int v : mesh.faces[f]) put_int(out, v);
    if (cells) put_int(out, mesh.face_cell[f]);
    if (colors)
      for (unsigned char c : mesh.face_color[f]) out.push_back(static_cast<char>(c));
  }
  file.write(out);
  file.close();
}

}  // namespace lrvd
