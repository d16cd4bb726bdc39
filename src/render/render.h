// Pictures of meshes and diagrams: a z-buffer rasterizer with an orthographic view, flat Lambert
// shading and outlines drawn where the region, the triangle or the depth under a pixel changes,
// and PNG output. What `lrvd render` draws (its scenes: render_scenes.h); the docs' images are made with it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "predicates/vec3.h"

namespace lrvd {

using Rgb = std::array<unsigned char, 3>;

//! What to draw: triangles with a colour and a region each, and points (the samples) as dots.
struct RenderScene {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Rgb> color;       //!< per triangle; empty: one light grey
  std::vector<int> region;      //!< per triangle; empty: one region. A dark line is drawn where it changes
  std::vector<char> hatched;    //!< per triangle; empty: none. Hatched triangles are striped dark
  std::vector<int> face;        //!< per triangle; empty: each its own. RenderOptions::edges draws
                                //!< a light line where it changes (a cell polygon's fan: its mesh triangle)
  std::vector<Vec3> points;     //!< drawn as dots where the surface does not hide them
};

//! The view and the picture. The camera looks at the middle of the scene's bounding box from the
//! direction given by the azimuth (about the up axis, 0: from the axis after the up axis, +z for
//! up y, +x for up z, +y for up x) and the elevation (towards the up axis); the scene fills the
//! picture but for a margin.
struct RenderOptions {
  int width = 1200;              //!< pixels, 16 to 4096
  int height = 900;              //!< pixels, 16 to 4096
  double azimuth = 30;           //!< degrees
  double elevation = 20;         //!< degrees, -90 to 90
  int up_axis = 1;               //!< 0 x, 1 y, 2 z
  bool up_negative = false;      //!< up is the axis' negative direction
  bool edges = false;            //!< also outline every face (RenderScene::face: a mesh's own edges)
  double point_radius = 0;       //!< dot radius in pixels; 0: from the picture's size and the
                                 //!< points' spacing (none when they are closer than ~4 pixels)
  int supersample = 3;           //!< samples per pixel side (anti-aliasing), 1 to 4; lowered
                                 //!< for large pictures to keep the buffers (8 bytes a sample)
                                 //!< at 24 M samples at most
};

//! Sets RenderOptions::up_axis and up_negative from "x", "y", "z", "-x", "-y" or "-z" (`--up`).
//! \throw InputError on any other text.
void set_up_axis(const std::string& text, RenderOptions& options);

//! An 8-bit RGB picture, rows from the top.
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  //!< width * height * 3
  Rgb pixel(int x, int y) const {
    const std::size_t k = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

//! The grey of a triangle without a colour of its own.
constexpr Rgb kRenderGrey = {205, 205, 210};

//! \throw InputError when the scene has no triangles, an index out of range, per-triangle lists of
//!        another length than the triangles, or a coordinate that is not finite.
void check_render_scene(const RenderScene& scene);

//! The scene drawn from the options' view on a white background.
//! \throw InputError on options out of range, a scene without triangles, indices out of range,
//!        per-triangle lists of another length than the triangles, or a coordinate that is not finite.
Image render(const RenderScene& scene, const RenderOptions& options = {});

//! Writes the image as a PNG, whole or not at all (as every writer of lrvd).
//! \throw InputError when the file cannot be written.
void write_png(const std::string& path, const Image& image);

}  // namespace lrvd
