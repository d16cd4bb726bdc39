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
#include "io/mesh_io.h"

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

Image render(const RenderScene& scene, const RenderOptions& options) {
  check_options(options);
  check_render_scene(scene);
  const View view = make_view(options);

  int ss = options.supersample;
  while (ss > 1 && static_cast<double>(options.width) * options.height * ss * ss > kMaxSamples) --ss;
  const int W = options.width * ss, H = options.height * ss;

  // Relative to the bounding box's middle: far from the origin, floats keep their digits.
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec3 hi = -1.0 * lo;
  for (const auto& t : scene.triangles)
    for (int v : t)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], scene.positions[v][c]);
        hi[c] = std::max(hi[c], scene.positions[v][c]);
      }
  const Vec3 middle = 0.5 * (lo + hi);
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  if (!std::isfinite(extent) || !is_finite(middle))
    throw InputError("render: the scene is too large to draw in doubles (its bounding box's size overflows)");
  if (extent > 0 && extent < 1e-290)
    throw InputError("render: the scene is too small to draw in doubles (its bounding box's size underflows)");
  // Everything below in units of the box's largest side: depths stored as floats and the areas
  // and normals of a scene 1e200 across neither overflow nor vanish.
  const double to_unit = extent > 0 ? 1 / extent : 1;
  auto unit_position = [&](const Vec3& p) { return (p - middle) * to_unit; };
  std::vector<Vec3> position(scene.positions.size());
  for (std::size_t v = 0; v < position.size(); ++v) position[v] = unit_position(scene.positions[v]);

  struct Projected {
    double x, y, depth;
  };
  auto project_raw = [&](const Vec3& d) { return Projected{dot(d, view.right), dot(d, view.up), dot(d, view.toward)}; };
  double xmin = std::numeric_limits<double>::max(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const auto& t : scene.triangles)
    for (int v : t) {
      const Projected q = project_raw(position[v]);
      xmin = std::min(xmin, q.x), xmax = std::max(xmax, q.x);
      ymin = std::min(ymin, q.y), ymax = std::max(ymax, q.y);
    }
  const double usable = 1 - 2 * kMargin;
  double scale = std::numeric_limits<double>::infinity();
  if (xmax > xmin) scale = std::min(scale, usable * W / (xmax - xmin));
  if (ymax > ymin) scale = std::min(scale, usable * H / (ymax - ymin));
  if (!(xmax > xmin) && !(ymax > ymin)) scale = 1;  // every vertex at one point
  const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
  auto project = [&](const Vec3& p) {
    const Projected q = project_raw(p);
    return Projected{0.5 * W + (q.x - cx) * scale, 0.5 * H - (q.y - cy) * scale, q.depth};
  };

  // Depth (larger is nearer) and triangle of every sample.
  const std::size_t count = static_cast<std::size_t>(W) * H;
  std::vector<float> depth(count, -std::numeric_limits<float>::infinity());
  std::vector<int> owner(count, -1);
  auto put = [&](int x, int y, float z, int t) {
    if (x < 0 || y < 0 || x >= W || y >= H) return;
    const std::size_t k = static_cast<std::size_t>(y) * W + x;
    if (z > depth[k]) {
      depth[k] = z;
      owner[k] = t;
    }
  };
  // A segment a pixel wide (ss samples), its depth interpolated along it.
  auto line = [&](const Projected& p, const Projected& q, int t) {
    const int steps = static_cast<int>(std::ceil(std::max(std::abs(q.x - p.x), std::abs(q.y - p.y)))) + 1;
    for (int k = 0; k <= steps; ++k) {
      const double f = static_cast<double>(k) / steps;
      const int x = static_cast<int>(std::floor(p.x + f * (q.x - p.x))) - ss / 2;
      const int y = static_cast<int>(std::floor(p.y + f * (q.y - p.y))) - ss / 2;
      const float z = static_cast<float>(p.depth + f * (q.depth - p.depth));
      for (int dy = 0; dy < ss; ++dy)
        for (int dx = 0; dx < ss; ++dx) put(x + dx, y + dy, z, t);
    }
  };
  // Triangles drawn as lines take no outline of their own: the line is the triangle, in its colour.
  std::vector<char> drawn_as_line(scene.triangles.size(), 0);
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& tri = scene.triangles[t];
    const Projected a = project(position[tri[0]]), b = project(position[tri[1]]), c = project(position[tri[2]]);
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    // A triangle seen edge-on, or so thin that it may miss every sample's centre, is drawn as its
    // edges too: a flat sheet seen from its side is a line, not nothing.
    const double longest = std::max({std::hypot(b.x - a.x, b.y - a.y), std::hypot(c.x - b.x, c.y - b.y),
                                      std::hypot(a.x - c.x, a.y - c.y)});
    if (!(std::abs(area) >= 1.5 * longest)) {
      drawn_as_line[t] = 1;
      line(a, b, static_cast<int>(t));
      line(b, c, static_cast<int>(t));
      line(c, a, static_cast<int>(t));
    }
    if (area == 0 || !std::isfinite(area)) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
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
        put(x, y, static_cast<float>(wa * a.depth + wb * b.depth + wc * c.depth), static_cast<int>(t));
      }
    }
  }

  // Shading per triangle: flat Lambert from a light a little above and right of the camera, both
  // sides lit, the back side greyed (the inside of an open surface).
  const Vec3 light = unit(view.toward + 0.4 * view.up + 0.25 * view.right);
  std::vector<std::array<float, 3>> shade(scene.triangles.size());
  double area = 0;  // of the surface, for the spacings below
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const auto& tri = scene.triangles[t];
    const Vec3& p0 = position[tri[0]];
    const Vec3 normal = cross(position[tri[1]] - p0, position[tri[2]] - p0);
    area += 0.5 * norm(normal);
    const Vec3 n = unit(normal);
    const double lambert = std::abs(dot(n, light));
    // A triangle without a normal (collinear corners) is drawn unshaded, in its full colour.
    const double intensity = squared_norm(n) > 0 ? 0.38 + 0.62 * lambert : 1.0;
    const Rgb base = scene.color.empty() ? kRenderGrey : scene.color[t];
    const bool back = dot(n, view.toward) < 0;
    for (int c = 0; c < 3; ++c) {
      const double value = back ? 0.5 * base[c] + 0.5 * 150 : base[c];
      shade[t][c] = static_cast<float>(value * intensity);
    }
  }

  // Mean spacing on the picture, in pixels, of `things` that tile the surface.
  auto spacing_px = [&](std::size_t things) { return std::sqrt(area / std::max<std::size_t>(things, 1)) * scale / ss; };
  // Lines between regions (or faces) a few pixels apart would cover them: below 4 (3) pixels
  // apart on average they are left out, and the colours alone tell the regions apart.
  bool region_lines = !scene.region.empty();
  if (region_lines) {
    std::vector<int> regions = scene.region;
    std::sort(regions.begin(), regions.end());
    region_lines = spacing_px(static_cast<std::size_t>(std::unique(regions.begin(), regions.end()) - regions.begin())) >= 4;
  }
  bool face_lines = options.edges;
  if (face_lines) {
    std::size_t faces = scene.triangles.size();
    if (!scene.face.empty()) {
      std::vector<int> f = scene.face;
      std::sort(f.begin(), f.end());
      faces = static_cast<std::size_t>(std::unique(f.begin(), f.end()) - f.begin());
    }
    face_lines = spacing_px(faces) >= 3;
  }

  // Outlines, each checked against the samples up to `reach` away along the rows and columns.
  const int reach = std::max(1, (ss + 1) / 2);
  const double occlusion_gap = 0.01;  // of the box's largest side
  const int stripe = std::max(2, 4 * ss);
  auto line_at = [&](int x, int y) -> float {
    // Returns the factor the sample's colour is multiplied by: 1 (no line) down to 0 (black).
    const std::size_t k = static_cast<std::size_t>(y) * W + x;
    const int t = owner[k];
    if (drawn_as_line[t]) return 1.0f;
    float factor = 1;
    for (int r = 1; r <= reach; ++r) {
      const int nx[4] = {x - r, x + r, x, x};
      const int ny[4] = {y, y, y - r, y + r};
      for (int d = 0; d < 4; ++d) {
        if (nx[d] < 0 || ny[d] < 0 || nx[d] >= W || ny[d] >= H) continue;
        const std::size_t m = static_cast<std::size_t>(ny[d]) * W + nx[d];
        const int u = owner[m];
        if (u == t) continue;
        if (u < 0) return 0.1f;  // the silhouette, drawn on the surface's side
        const bool nearer = depth[k] >= depth[m];
        if (nearer && depth[k] - depth[m] > occlusion_gap && !share_vertex(scene.triangles[t], scene.triangles[u]))
          return 0.1f;  // a part in front of another
        if (region_lines && scene.region[t] != scene.region[u]) factor = std::min(factor, 0.2f);
        else if (face_lines && (scene.face.empty() || scene.face[t] != scene.face[u])) factor = std::min(factor, 0.55f);
      }
    }
    return factor;
  };

  Image image;
  image.width = options.width;
  image.height = options.height;
  image.rgb.assign(static_cast<std::size_t>(options.width) * options.height * 3, 255);
  tbb::parallel_for(tbb::blocked_range<int>(0, options.height), [&](const tbb::blocked_range<int>& rows) {
    for (int py = rows.begin(); py != rows.end(); ++py)
      for (int px = 0; px < options.width; ++px) {
        float sum[3] = {0, 0, 0};
        for (int sy = 0; sy < ss; ++sy)
          for (int sx = 0; sx < ss; ++sx) {
            const int x = px * ss + sx, y = py * ss + sy;
            const int t = owner[static_cast<std::size_t>(y) * W + x];
            if (t < 0) {
              for (float& s : sum) s += 255;
              continue;
            }
            float f = line_at(x, y);
            if (!scene.hatched.empty() && scene.hatched[t] && ((x + y) / stripe) % 2 == 0) f *= 0.45f;
            for (int c = 0; c < 3; ++c) sum[c] += shade[t][c] * f;
          }
        unsigned char* out = &image.rgb[3 * (static_cast<std::size_t>(py) * options.width + px)];
        for (int c = 0; c < 3; ++c)
          out[c] = static_cast<unsigned char>(std::clamp(std::lround(sum[c] / (ss * ss)), 0L, 255L));
      }
  });

  // The points as dots, where the surface does not hide them (a point on the surface is as deep
  // as the surface there, up to the depth's change over a couple of samples). Unless given, the
  // radius is a sixth of the points' mean spacing on the picture, at most 1/260 of its size and
  // at least 0.7 pixels: points any closer are not drawn, they would cover the surface.
  double radius = options.point_radius;
  if (radius == 0 && !scene.points.empty()) {
    radius = std::min(std::clamp(std::min(options.width, options.height) / 260.0, 1.5, 6.0), spacing_px(scene.points.size()) / 6);
    if (radius < 0.7) radius = 0;
  }
  const double hidden_gap = 0.001 + 2 / scale;
  for (const Vec3& p : radius > 0 ? scene.points : std::vector<Vec3>{}) {
    const Projected q = project(unit_position(p));
    if (!(q.x >= 0 && q.y >= 0 && q.x < W && q.y < H)) continue;  // off the picture (or not finite)
    const int x = static_cast<int>(q.x), y = static_cast<int>(q.y);
    const std::size_t k = static_cast<std::size_t>(y) * W + x;
    if (owner[k] >= 0 && depth[k] - q.depth > hidden_gap) continue;
    const double cxp = q.x / ss, cyp = q.y / ss;  // in pixels
    const int r = static_cast<int>(std::ceil(radius + 1));
    for (int py = static_cast<int>(cyp) - r; py <= static_cast<int>(cyp) + r; ++py)
      for (int px = static_cast<int>(cxp) - r; px <= static_cast<int>(cxp) + r; ++px) {
        if (px < 0 || py < 0 || px >= options.width || py >= options.height) continue;
        // Coverage of the pixel by the disc, from the distance of its centre (a one-pixel ramp).
        const double d = std::hypot(px + 0.5 - cxp, py + 0.5 - cyp);
        const double cover = std::clamp(radius + 0.5 - d, 0.0, 1.0);
        if (cover <= 0) continue;
        unsigned char* out = &image.rgb[3 * (static_cast<std::size_t>(py) * options.width + px)];
        for (int c = 0; c < 3; ++c) out[c] = static_cast<unsigned char>(std::lround(out[c] * (1 - cover) + 20 * cover));
      }
  }
  return image;
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
