// The rasterizer behind `lrvd render`: triangles into a supersampled depth and triangle buffer,
// then one pass that shades each sample, draws the outlines from the buffers' neighbours and
// averages the samples into pixels.
#include "render/render.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "io/mesh_writers.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace lrvd {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Supersampled buffers (a float depth and an int triangle a sample) stay under about 200 MB.
constexpr double kMaxSamples = 24e6;
constexpr double kMargin = 0.04;  // of the picture's size, on each side

void check_options(const RenderOptions& o) {
  auto fail = [](const std::string& what) { throw InputError("render: " + what); };
  if (o.width < 16 || o.width > 4096 || o.height < 16 || o.height > 4096)
    fail(fmt::format("a picture is 16 to 4096 pixels wide and high, not {} x {}", o.width, o.height));
  if (!std::isfinite(o.azimuth)) fail("the azimuth is not a finite number");
  if (!(o.elevation >= -90 && o.elevation <= 90))
    fail(fmt::format("the elevation is -90 to 90 degrees, not {}", o.elevation));
  if (o.up_axis < 0 || o.up_axis > 2) fail(fmt::format("the up axis is 0, 1 or 2, not {}", o.up_axis));
  if (o.supersample < 1 || o.supersample > 4) fail(fmt::format("supersampling is 1 to 4, not {}", o.supersample));
  if (!(o.point_radius >= 0 && o.point_radius <= 100))
    fail(fmt::format("the dot radius is 0 to 100 pixels, not {}", o.point_radius));
}

}  // namespace

void check_render_scene(const RenderScene& s) {
  auto fail = [](const std::string& what) { throw InputError("render: " + what); };
  const std::size_t nt = s.triangles.size();
  if (nt == 0) fail("the scene has no triangles");
  const int nv = static_cast<int>(s.positions.size());
  for (std::size_t t = 0; t < nt; ++t)
    for (int v : s.triangles[t])
      if (v < 0 || v >= nv) fail(fmt::format("triangle {} has vertex {}, not one of the {} positions", t, v, nv));
  auto per_triangle = [&](std::size_t size, const char* what) {
    if (size != 0 && size != nt) fail(fmt::format("{} {} for {} triangles", size, what, nt));
  };
  per_triangle(s.color.size(), "colours");
  per_triangle(s.region.size(), "regions");
  per_triangle(s.hatched.size(), "hatch flags");
  per_triangle(s.face.size(), "faces");
  for (const Vec3& p : s.positions)
    if (!is_finite(p)) fail("a position is not finite");
  for (const Vec3& p : s.points)
    if (!is_finite(p)) fail("a point is not finite");
}

namespace {

// The camera's frame: right, up on the picture, and towards the camera.
struct View {
  Vec3 right, up, toward;
};

View make_view(const RenderOptions& o) {
  Vec3 up_axis, front;
  up_axis[o.up_axis] = o.up_negative ? -1 : 1;
  front[(o.up_axis + 1) % 3] = 1;
  const Vec3 side = cross(up_axis, front);
  // Reduced first: a huge azimuth (1e308) would overflow in radians.
  const double az = std::fmod(o.azimuth, 360.0) * kPi / 180, el = o.elevation * kPi / 180;
  const Vec3 horizontal = std::cos(az) * front + std::sin(az) * side;
  View v;
  v.toward = unit(std::cos(el) * horizontal + std::sin(el) * up_axis);
  v.right = unit(cross(up_axis, horizontal));  // well defined even looking straight down
  v.up = cross(v.toward, v.right);
  return v;
}

bool share_vertex(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  for (int u : a)
    for (int w : b)
      if (u == w) return true;
  return false;
}

}  // namespace

void set_up_axis(const std::string& text, RenderOptions& options) {
  const bool negative = !text.empty() && text[0] == '-';
  const std::string axis = negative ? text.substr(1) : text;
  if (axis != "x" && axis != "y" && axis != "z")
    throw InputError(fmt::format("--up takes x, y, z, -x, -y or -z, not '{}'", text));
  options.up_axis = axis[0] - 'x';
  options.up_negative = negative;
}

namespace {

// A point on the picture, in samples, and its depth (larger is nearer).
struct Projected {
  double x, y, depth;
};

// The state render's steps share: the scene in units of its box, the camera, the supersampled
// depth and triangle buffers and the shade of each triangle. The steps, in order: place the scene,
// fit it to the picture, rasterize, shade, choose the outlines, resolve the samples into pixels,
// draw the points.
class Renderer {
 public:
  Renderer(const RenderScene& scene, const RenderOptions& options)
      : scene_(scene), options_(options), view_(make_view(options)) {
    ss_ = options.supersample;
    while (ss_ > 1 && static_cast<double>(options.width) * options.height * ss_ * ss_ > kMaxSamples) --ss_;
    W_ = options.width * ss_, H_ = options.height * ss_;
  }

  Image run() {
    place_in_unit_box();
    fit_to_picture();
    rasterize();
    shade_triangles();
    choose_lines();
    Image image = resolve_pixels();
    draw_points(image);
    return image;
  }

 private:
  void place_in_unit_box();
  void fit_to_picture();
  void rasterize();
  void fill_triangle(int t, const Projected& a, const Projected& b, const Projected& c, double area);
  void shade_triangles();
  void choose_lines();
  Image resolve_pixels() const;
  float line_at(int x, int y) const;
  void draw_points(Image& image) const;

  Vec3 unit_position(const Vec3& p) const { return (p - middle_) * to_unit_; }
  Projected project_raw(const Vec3& d) const { return Projected{dot(d, view_.right), dot(d, view_.up), dot(d, view_.toward)}; }
  Projected project(const Vec3& p) const {
    const Projected q = project_raw(p);
    return Projected{0.5 * W_ + (q.x - cx_) * scale_, 0.5 * H_ - (q.y - cy_) * scale_, q.depth};
  }
  void put(int x, int y, float z, int t) {
    if (x < 0 || y < 0 || x >= W_ || y >= H_) return;
    const std::size_t k = static_cast<std::size_t>(y) * W_ + x;
    if (z > depth_[k]) {
      depth_[k] = z;
      owner_[k] = t;
    }
  }
  void line(const Projected& p, const Projected& q, int t);
  // Mean spacing on the picture, in pixels, of `things` that tile the surface.
  double spacing_px(std::size_t things) const {
    return std::sqrt(area_ / std::max<std::size_t>(things, 1)) * scale_ / ss_;
  }

  const RenderScene& scene_;
  const RenderOptions& options_;
  const View view_;
  int ss_, W_, H_;  // the supersampling and the buffers' size in samples
  Vec3 middle_;
  double to_unit_ = 1;
  std::vector<Vec3> position_;  // of the scene's vertices, in units of the box's largest side
  double scale_ = 1, cx_ = 0, cy_ = 0;
  std::vector<float> depth_;  // of every sample (larger is nearer)
  std::vector<int> owner_;    // the triangle of every sample, -1 for none
  std::vector<char> drawn_as_line_;
  std::vector<std::array<float, 3>> shade_;
  double area_ = 0;  // of the surface, for the spacings
  bool region_lines_ = false, face_lines_ = false;
};

// Relative to the bounding box's middle: far from the origin, floats keep their digits.
void Renderer::place_in_unit_box() {
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec3 hi = -1.0 * lo;
  for (const auto& t : scene_.triangles)
    for (int v : t)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], scene_.positions[v][c]);
        hi[c] = std::max(hi[c], scene_.positions[v][c]);
      }
  middle_ = 0.5 * (lo + hi);
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  if (!std::isfinite(extent) || !is_finite(middle_))
    throw InputError("render: the scene is too large to draw in doubles (its bounding box's size overflows)");
  if (extent > 0 && extent < 1e-290)
    throw InputError("render: the scene is too small to draw in doubles (its bounding box's size underflows)");
  // Everything below in units of the box's largest side: depths stored as floats and the areas
  // and normals of a scene 1e200 across neither overflow nor vanish.
  to_unit_ = extent > 0 ? 1 / extent : 1;
  position_.resize(scene_.positions.size());
  for (std::size_t v = 0; v < position_.size(); ++v) position_[v] = unit_position(scene_.positions[v]);
}

// The scale and centre that fit the projected scene into the picture, within its margins.
void Renderer::fit_to_picture() {
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const auto& t : scene_.triangles)
    for (int v : t) {
      const Projected q = project_raw(position_[v]);
      xmin = std::min(xmin, q.x), xmax = std::max(xmax, q.x);
      ymin = std::min(ymin, q.y), ymax = std::max(ymax, q.y);
    }
  const double usable = 1 - 2 * kMargin;
  scale_ = std::numeric_limits<double>::infinity();
  if (xmax > xmin) scale_ = std::min(scale_, usable * W_ / (xmax - xmin));
  if (ymax > ymin) scale_ = std::min(scale_, usable * H_ / (ymax - ymin));
  if (!(xmax > xmin) && !(ymax > ymin)) scale_ = 1;  // every vertex at one point
  cx_ = 0.5 * (xmin + xmax), cy_ = 0.5 * (ymin + ymax);
}

// A segment a pixel wide (ss samples), its depth interpolated along it.
void Renderer::line(const Projected& p, const Projected& q, int t) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(q.x - p.x), std::abs(q.y - p.y)))) + 1;
  for (int k = 0; k <= steps; ++k) {
    const double f = static_cast<double>(k) / steps;
    const int x = static_cast<int>(std::floor(p.x + f * (q.x - p.x))) - ss_ / 2;
    const int y = static_cast<int>(std::floor(p.y + f * (q.y - p.y))) - ss_ / 2;
    const float z = static_cast<float>(p.depth + f * (q.depth - p.depth));
    for (int dy = 0; dy < ss_; ++dy)
      for (int dx = 0; dx < ss_; ++dx) put(x + dx, y + dy, z, t);
  }
}

// Depth and triangle of every sample.
void Renderer::rasterize() {
  const std::size_t count = static_cast<std::size_t>(W_) * H_;
  depth_.assign(count, -std::numeric_limits<float>::infinity());
  owner_.assign(count, -1);
  // Triangles drawn as lines take no outline of their own: the line is the triangle, in its colour.
  drawn_as_line_.assign(scene_.triangles.size(), 0);
  for (std::size_t t = 0; t < scene_.triangles.size(); ++t) {
    const auto& tri = scene_.triangles[t];
    const Projected a = project(position_[tri[0]]), b = project(position_[tri[1]]), c = project(position_[tri[2]]);
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    // A triangle seen edge-on, or so thin that it may miss every sample's centre, is drawn as its
    // edges too: a flat sheet seen from its side is a line, not nothing.
    const double longest = std::max({std::hypot(b.x - a.x, b.y - a.y), std::hypot(c.x - b.x, c.y - b.y),
                                      std::hypot(a.x - c.x, a.y - c.y)});
    if (!(std::abs(area) >= 1.5 * longest)) {
      drawn_as_line_[t] = 1;
      line(a, b, static_cast<int>(t));
      line(b, c, static_cast<int>(t));
      line(c, a, static_cast<int>(t));
    }
    if (area == 0 || !std::isfinite(area)) continue;
    fill_triangle(static_cast<int>(t), a, b, c, area);
  }
}

// The samples whose centres the triangle (a, b, c) of twice the signed `area` covers, row by row.
void Renderer::fill_triangle(int t, const Projected& a, const Projected& b, const Projected& c, double area) {
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(W_ - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(H_ - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  const double inv = 1 / area;
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    // The row's samples inside the triangle form one run: each barycentric weight is linear in
    // px, A + B px, and the run is where all three are non-negative. The run is widened by a
    // sample each way and the samples in it are tested as before, so a sliver costs its height
    // and its area, not its bounding box.
    const double a_a = (b.x * (c.y - py) - (b.y - py) * c.x) * inv, b_a = (b.y - c.y) * inv;
    const double a_b = (c.x * (a.y - py) - (c.y - py) * a.x) * inv, b_b = (c.y - a.y) * inv;
    double lo = x0, hi = x1 + 1.0;  // in px, within the box's row
    for (const auto& [offset, slope] : {std::pair{a_a, b_a}, std::pair{a_b, b_b}, std::pair{1 - a_a - a_b, -b_a - b_b}}) {
      if (slope > 0) lo = std::max(lo, -offset / slope);
      if (slope < 0) hi = std::min(hi, -offset / slope);
    }
    int from = x0, to = x1;
    if (std::isfinite(lo) && std::isfinite(hi)) {  // else every sample of the box's row is tested
      if (lo > hi + 2) continue;
      from = std::max(x0, static_cast<int>(std::floor(lo - 0.5)) - 1);
      to = std::min(x1, static_cast<int>(std::ceil(hi - 0.5)) + 1);
    }
    for (int x = from; x <= to; ++x) {
      const double px = x + 0.5;
      const double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) * inv;
      const double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) * inv;
      const double wc = 1 - wa - wb;
      if (wa < 0 || wb < 0 || wc < 0) continue;
      put(x, y, static_cast<float>(wa * a.depth + wb * b.depth + wc * c.depth), t);
    }
  }
}

// Shading per triangle: flat Lambert from a light a little above and right of the camera, both
// sides lit, the back side greyed (the inside of an open surface).
void Renderer::shade_triangles() {
  const Vec3 light = unit(view_.toward + 0.4 * view_.up + 0.25 * view_.right);
  shade_.resize(scene_.triangles.size());
  area_ = 0;
  for (std::size_t t = 0; t < scene_.triangles.size(); ++t) {
    const auto& tri = scene_.triangles[t];
    const Vec3& p0 = position_[tri[0]];
    const Vec3 normal = cross(position_[tri[1]] - p0, position_[tri[2]] - p0);
    area_ += 0.5 * norm(normal);
    const Vec3 n = unit(normal);
    const double lambert = std::abs(dot(n, light));
    // A triangle without a normal (collinear corners) is drawn unshaded, in its full colour.
    const double intensity = squared_norm(n) > 0 ? 0.38 + 0.62 * lambert : 1.0;
    const Rgb base = scene_.color.empty() ? kRenderGrey : scene_.color[t];
    const bool back = dot(n, view_.toward) < 0;
    for (int c = 0; c < 3; ++c) {
      const double value = back ? 0.5 * base[c] + 0.5 * 150 : base[c];
      shade_[t][c] = static_cast<float>(value * intensity);
    }
  }
}

// Lines between regions (or faces) a few pixels apart would cover them: below 4 (3) pixels
// apart on average they are left out, and the colours alone tell the regions apart.
void Renderer::choose_lines() {
  region_lines_ = !scene_.region.empty();
  if (region_lines_) {
    std::vector<int> regions = scene_.region;
    std::sort(regions.begin(), regions.end());
    region_lines_ = spacing_px(static_cast<std::size_t>(std::unique(regions.begin(), regions.end()) - regions.begin())) >= 4;
  }
  face_lines_ = options_.edges;
  if (face_lines_) {
    std::size_t faces = scene_.triangles.size();
    if (!scene_.face.empty()) {
      std::vector<int> f = scene_.face;
      std::sort(f.begin(), f.end());
      faces = static_cast<std::size_t>(std::unique(f.begin(), f.end()) - f.begin());
    }
    face_lines_ = spacing_px(faces) >= 3;
  }
}

// The factor the colour of sample (x, y) is multiplied by: 1 (no line) down to 0 (black). Outlines
// are checked against the samples up to `reach` away along the rows and columns.
float Renderer::line_at(int x, int y) const {
  const int reach = std::max(1, (ss_ + 1) / 2);
  const double occlusion_gap = 0.01;  // of the box's largest side
  const std::size_t k = static_cast<std::size_t>(y) * W_ + x;
  const int t = owner_[k];
  if (drawn_as_line_[t]) return 1.0f;
  float factor = 1;
  for (int r = 1; r <= reach; ++r) {
    const int nx[4] = {x - r, x + r, x, x};
    const int ny[4] = {y, y, y - r, y + r};
    for (int d = 0; d < 4; ++d) {
      if (nx[d] < 0 || ny[d] < 0 || nx[d] >= W_ || ny[d] >= H_) continue;
      const std::size_t m = static_cast<std::size_t>(ny[d]) * W_ + nx[d];
      const int u = owner_[m];
      if (u == t) continue;
      if (u < 0) return 0.1f;  // the silhouette, drawn on the surface's side
      const bool nearer = depth_[k] >= depth_[m];
      if (nearer && depth_[k] - depth_[m] > occlusion_gap && !share_vertex(scene_.triangles[t], scene_.triangles[u]))
        return 0.1f;  // a part in front of another
      if (region_lines_ && scene_.region[t] != scene_.region[u]) factor = std::min(factor, 0.2f);
      else if (face_lines_ && (scene_.face.empty() || scene_.face[t] != scene_.face[u])) factor = std::min(factor, 0.55f);
    }
  }
  return factor;
}

// Each pixel the mean of its samples: shaded, outlined, hatched where asked; white where empty.
Image Renderer::resolve_pixels() const {
  const int stripe = std::max(2, 4 * ss_);
  Image image;
  image.width = options_.width;
  image.height = options_.height;
  image.rgb.assign(static_cast<std::size_t>(options_.width) * options_.height * 3, 255);
  tbb::parallel_for(tbb::blocked_range<int>(0, options_.height), [&](const tbb::blocked_range<int>& rows) {
    for (int py = rows.begin(); py != rows.end(); ++py)
      for (int px = 0; px < options_.width; ++px) {
        float sum[3] = {0, 0, 0};
        for (int sy = 0; sy < ss_; ++sy)
          for (int sx = 0; sx < ss_; ++sx) {
            const int x = px * ss_ + sx, y = py * ss_ + sy;
            const int t = owner_[static_cast<std::size_t>(y) * W_ + x];
            if (t < 0) {
              for (float& s : sum) s += 255;
              continue;
            }
            float f = line_at(x, y);
            if (!scene_.hatched.empty() && scene_.hatched[t] && ((x + y) / stripe) % 2 == 0) f *= 0.45f;
            for (int c = 0; c < 3; ++c) sum[c] += shade_[t][c] * f;
          }
        unsigned char* out = &image.rgb[3 * (static_cast<std::size_t>(py) * options_.width + px)];
        for (int c = 0; c < 3; ++c)
          out[c] = static_cast<unsigned char>(std::clamp(std::lround(sum[c] / (ss_ * ss_)), 0L, 255L));
      }
  });
  return image;
}

// The points as dots, where the surface does not hide them (a point on the surface is as deep
// as the surface there, up to the depth's change over a couple of samples). Unless given, the
// radius is a sixth of the points' mean spacing on the picture, at most 1/260 of its size and
// at least 0.7 pixels: points any closer are not drawn, they would cover the surface.
void Renderer::draw_points(Image& image) const {
  double radius = options_.point_radius;
  if (radius == 0 && !scene_.points.empty()) {
    radius = std::min(std::clamp(std::min(options_.width, options_.height) / 260.0, 1.5, 6.0), spacing_px(scene_.points.size()) / 6);
    if (radius < 0.7) radius = 0;
  }
  const double hidden_gap = 0.001 + 2 / scale_;
  for (const Vec3& p : radius > 0 ? scene_.points : std::vector<Vec3>{}) {
    const Projected q = project(unit_position(p));
    if (!(q.x >= 0 && q.y >= 0 && q.x < W_ && q.y < H_)) continue;  // off the picture (or not finite)
    const int x = static_cast<int>(q.x), y = static_cast<int>(q.y);
    const std::size_t k = static_cast<std::size_t>(y) * W_ + x;
    if (owner_[k] >= 0 && depth_[k] - q.depth > hidden_gap) continue;
    const double cxp = q.x / ss_, cyp = q.y / ss_;  // in pixels
    const int r = static_cast<int>(std::ceil(radius + 1));
    for (int py = static_cast<int>(cyp) - r; py <= static_cast<int>(cyp) + r; ++py)
      for (int px = static_cast<int>(cxp) - r; px <= static_cast<int>(cxp) + r; ++px) {
        if (px < 0 || py < 0 || px >= options_.width || py >= options_.height) continue;
        // Coverage of the pixel by the disc, from the distance of its centre (a one-pixel ramp).
        const double d = std::hypot(px + 0.5 - cxp, py + 0.5 - cyp);
        const double cover = std::clamp(radius + 0.5 - d, 0.0, 1.0);
        if (cover <= 0) continue;
        unsigned char* out = &image.rgb[3 * (static_cast<std::size_t>(py) * options_.width + px)];
        for (int c = 0; c < 3; ++c) out[c] = static_cast<unsigned char>(std::lround(out[c] * (1 - cover) + 20 * cover));
      }
  }
}

}  // namespace

Image render(const RenderScene& scene, const RenderOptions& options) {
  check_options(options);
  check_render_scene(scene);
  return Renderer(scene, options).run();
}

void write_png(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw InputError(fmt::format("{}: the picture's pixels do not match its size {} x {}", path, image.width, image.height));
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 3, image.rgb.data(), image.width * 3))
    throw InputError(fmt::format("{}: the PNG could not be encoded", path));
  write_text_file(path, bytes);
}

}  // namespace lrvd
