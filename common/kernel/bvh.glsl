// The nearest-triangle search through the bounding volume hierarchy (common/scene/bvh.h
// builds it on the host): the step after the article's GPU section, which ends "yet without
// an acceleration structure". The same hits as the brute force of intersect.glsl, bit for
// bit: t, triangle and barycentrics (tests/common/kernel/test_bvh_traversal.cpp). This is
// the walk in its plain form, the CPU's when it has no wide BVH (its fast path is
// cpu/wide_bvh*); the GPU runs the same walk tuned for lavapipe (gpu/bvh_walk.glsl).
#ifndef PT_BVH_GLSL
#define PT_BVH_GLSL

#include "common/kernel/bvh_hit.glsl"

// The nearest hit of `best` and every triangle, found by walking the BVH with a stack of
// the nodes still to visit, each with the distance at which the ray enters its box. A node
// popped from the stack is skipped if a hit nearer than that distance has been found since
// it was pushed; a leaf's triangles are tested by hit_triangle_tie(); an inner node pushes
// the children whose boxes the ray passes through, the farther one first, so that the
// nearer one is visited next (its hits then let more of the farther one be skipped). No
// recursion: the stack is an array of kBvhStackSize, as deep as the build lets the tree
// grow (one pending sibling per level, and the two children of the node just popped).
Hit nearest_triangle_bvh(Ray ray, RayShear rs, Hit best) {
  if (params.triangle_count == 0u) return best;
  vec3 inv_dir = inverse_direction(ray.dir);
  uint stack_node[kBvhStackSize];  // the nodes still to visit: their indices
  float stack_t[kBvhStackSize];    // and where the ray enters their boxes
  uint top = 0u;                   // how many there are
  BvhNode root = bvh_node_at(0u);
  vec2 span = box_span(ray, inv_dir, root.lo, root.hi, best.t);
  if (span.x > span.y) return best;
  stack_node[0] = 0u;
  stack_t[0] = span.x;
  top = 1u;
  while (top > 0u) {
    top--;
    if (stack_t[top] > best.t) continue;  // a nearer hit was found since it was pushed
    BvhNode n = bvh_node_at(stack_node[top]);
    if (n.count > 0u) {  // a leaf: its triangles
      for (uint i = 0u; i < n.count; i++) best = hit_triangle_tie(ray, rs, bvh_index_at(n.first_or_left + i), best);
      continue;
    }
    uint left = n.first_or_left;  // an inner node: its children are left and left + 1
    BvhNode child_l = bvh_node_at(left);
    BvhNode child_r = bvh_node_at(left + 1u);
    vec2 span_l = box_span(ray, inv_dir, child_l.lo, child_l.hi, best.t);
    vec2 span_r = box_span(ray, inv_dir, child_r.lo, child_r.hi, best.t);
    bool left_first = span_l.x <= span_r.x;  // the nearer child; the left one on a tie
    uint near_child = left_first ? left : left + 1u;
    uint far_child = left_first ? left + 1u : left;
    vec2 near_span = left_first ? span_l : span_r;
    vec2 far_span = left_first ? span_r : span_l;
    if (far_span.x <= far_span.y) {
      stack_node[top] = far_child;
      stack_t[top] = far_span.x;
      top++;
    }
    if (near_span.x <= near_span.y) {
      stack_node[top] = near_child;
      stack_t[top] = near_span.x;
      top++;
    }
  }
  return best;
}

// Whether any triangle is hit closer than t_max (a shadow ray): the same walk, but the
// first hit found ends it, in any order, so no tie rule is needed, no child is put first
// and no entry distance is kept.
bool occluded_bvh(Ray ray, RayShear rs, float t_max) {
  if (params.triangle_count == 0u) return false;
  vec3 inv_dir = inverse_direction(ray.dir);
  Hit none = Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone);
  uint stack_node[kBvhStackSize];  // the nodes still to visit
  uint top = 0u;
  BvhNode root = bvh_node_at(0u);
  if (!hit_box(ray, inv_dir, root.lo, root.hi, t_max)) return false;
  stack_node[0] = 0u;
  top = 1u;
  while (top > 0u) {
    top--;
    BvhNode n = bvh_node_at(stack_node[top]);
    if (n.count > 0u) {  // a leaf: its triangles
      for (uint i = 0u; i < n.count; i++) {
        if (hit_triangle(ray, rs, bvh_index_at(n.first_or_left + i), none).kind != kPrimNone) return true;
      }
      continue;
    }
    uint left = n.first_or_left;  // an inner node: the children whose boxes the ray meets
    BvhNode child_l = bvh_node_at(left);
    BvhNode child_r = bvh_node_at(left + 1u);
    if (hit_box(ray, inv_dir, child_r.lo, child_r.hi, t_max)) {
      stack_node[top] = left + 1u;
      top++;
    }
    if (hit_box(ray, inv_dir, child_l.lo, child_l.hi, t_max)) {
      stack_node[top] = left;
      top++;
    }
  }
  return false;
}

#endif  // PT_BVH_GLSL
