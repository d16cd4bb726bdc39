// Points in a k-d tree (nanoflann): the one adaptor through which nanoflann reads them.
#pragma once

#include <cstddef>

#include <nanoflann.hpp>

namespace lrvd {

//! nanoflann's view of the points of a `View`: `view.size()` of them, the k-th at `view[k]` (a Vec3).
template <class View>
struct KdPoints {
  View view;
  std::size_t kdtree_get_point_count() const { return view.size(); }
  double kdtree_get_pt(std::size_t k, std::size_t axis) const { return view[k][static_cast<int>(axis)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // nanoflann computes the bounding box
  }
};

//! A k-d tree over KdPoints<View>, with squared Euclidean distances.
template <class View>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, KdPoints<View>>, KdPoints<View>, 3>;

}  // namespace lrvd
