// The GPU's walk through the bounding volume hierarchy (the step after the article's GPU
// section): common/kernel/bvh.glsl's walk, the same hits bit for bit, tuned for Mesa's
// lavapipe, where it runs neighbouring rays in lockstep: a packed stack, one loop per
// descent, the pop written twice. Why each one pays: docs/acceleration.md, "Measured".
#ifndef PT_GPU_BVH_WALK_GLSL
#define PT_GPU_BVH_WALK_GLSL

#include "common/kernel/bvh_hit.glsl"

// A pending node as the stack holds it: its first_or_left and count in one number
// (kBvhCountBits, scene_types.h), so that the stack is two arrays, not three: lavapipe reads
// and writes them invocation by invocation.
uint bvh_pending(uint first_or_left, uint count) { return (first_or_left << kBvhCountBits) | count; }
uint bvh_pending_first(uint pending) { return pending >> kBvhCountBits; }
uint bvh_pending_count(uint pending) { return pending & ((1u << kBvhCountBits) - 1u); }

// The nearest hit of `best` and every triangle: common/kernel/bvh.glsl's walk (the nearer
// child first, the farther one on the stack with its entry distance, the same tie rule), as
// lavapipe runs it fastest. The walk descends inner nodes in a loop of its own until it
// stands at a leaf, and only then tests triangles ("while-while", Aila and Laine 2009): a
// GPU runs neighbouring rays in lockstep, and a leaf's test, the costly step, then runs for
// all of them at once rather than again for each ray that reaches its leaf a step later.
Hit nearest_triangle_bvh(Ray ray, RayShear rs, Hit best) {
  if (params.triangle_count == 0u) return best;
  vec3 inv_dir = inverse_direction(ray.dir);
  BvhNode n = bvh_node_at(0u);  // the node the walk stands at: its first_or_left and count
  if (!hit_box(ray, inv_dir, n.lo, n.hi, best.t)) return best;
  // The pending nodes as bvh_pending(first_or_left, count) and entry distance: a pop reads no
  // node (reading it again after each pop was slower on lavapipe).
  uint stack_node[kBvhStackSize];
  float stack_t[kBvhStackSize];
  uint top = 0u;
  bool walking = true;
  while (walking) {
    // Inner nodes, down to a leaf. Both children's whole nodes are read, not just their
    // boxes: the child the walk goes on to, or pushes, is then at hand (on the GPU a node is
    // two texels whose fourth components hold first_or_left and count, so this costs no
    // extra read).
    while (n.count == 0u) {
      uint left = n.first_or_left;
      BvhNode child_l = bvh_node_at(left);
      BvhNode child_r = bvh_node_at(left + 1u);
      vec2 span_l = box_span(ray, inv_dir, child_l.lo, child_l.hi, best.t);
      vec2 span_r = box_span(ray, inv_dir, child_r.lo, child_r.hi, best.t);
      bool hit_l = span_l.x <= span_l.y;
      bool hit_r = span_r.x <= span_r.y;
      if (hit_l && hit_r) {
        bool left_first = span_l.x <= span_r.x;
        BvhNode far = left_first ? child_r : child_l;
        stack_node[top] = bvh_pending(far.first_or_left, far.count);
        stack_t[top] = left_first ? span_r.x : span_l.x;
        top++;
        n = left_first ? child_l : child_r;
      } else if (hit_l || hit_r) {
        n = hit_l ? child_l : child_r;
      } else {
        // Nothing below this node: the next pending node that a hit could still lie in. The
        // same pop as after a leaf, written here too so that a ray goes on down without
        // waiting for its neighbours' descents to end (one pop after the loop for both
        // cases was slower on lavapipe).
        walking = false;
        while (top > 0u && !walking) {
          top--;
          if (stack_t[top] <= best.t) {
            n.first_or_left = bvh_pending_first(stack_node[top]);
            n.count = bvh_pending_count(stack_node[top]);
            walking = true;
          }
        }
        if (!walking) break;
      }
    }
    if (!walking) break;
    // A leaf: its triangles, then the next pending node that a hit could still lie in.
    for (uint i = 0u; i < n.count; i++) best = hit_triangle_tie(ray, rs, bvh_index_at(n.first_or_left + i), best);
    walking = false;
    while (top > 0u && !walking) {
      top--;
      if (stack_t[top] <= best.t) {
        n.first_or_left = bvh_pending_first(stack_node[top]);
        n.count = bvh_pending_count(stack_node[top]);
        walking = true;
      }
    }
  }
  return best;
}

// Whether any triangle is hit closer than t_max (a shadow ray): the first hit found ends the
// walk, in any order, so no tie rule is needed and no child is put first. The same two loops
// as nearest_triangle_bvh: down the inner nodes, keeping one child and putting the other on
// the stack (one pending sibling per level, within kBvhStackSize), then a leaf's triangles.
// On lavapipe this traced about twice the shadow rays per second of the plain walk's one
// loop, which pops every node, leaves and inner nodes alike.
bool occluded_bvh(Ray ray, RayShear rs, float t_max) {
  if (params.triangle_count == 0u) return false;
  vec3 inv_dir = inverse_direction(ray.dir);
  Hit none = Hit(t_max, 0.0f, 0.0f, 0u, kPrimNone);
  // The pending nodes as bvh_pending(first_or_left, count), as in nearest_triangle_bvh.
  uint stack_node[kBvhStackSize];
  uint top = 0u;
  BvhNode n = bvh_node_at(0u);  // the node the walk stands at: its first_or_left and count
  if (!hit_box(ray, inv_dir, n.lo, n.hi, t_max)) return false;
  while (true) {  // each way out returns
    while (n.count == 0u) {
      BvhNode child_l = bvh_node_at(n.first_or_left);
      BvhNode child_r = bvh_node_at(n.first_or_left + 1u);
      bool hit_l = hit_box(ray, inv_dir, child_l.lo, child_l.hi, t_max);
      bool hit_r = hit_box(ray, inv_dir, child_r.lo, child_r.hi, t_max);
      if (hit_l && hit_r) {
        stack_node[top] = bvh_pending(child_r.first_or_left, child_r.count);
        top++;
        n = child_l;
      } else if (hit_l || hit_r) {
        n = hit_l ? child_l : child_r;
      } else {  // nothing below this node: the next pending one
        if (top == 0u) return false;
        top--;
        n.first_or_left = bvh_pending_first(stack_node[top]);
        n.count = bvh_pending_count(stack_node[top]);
      }
    }
    for (uint i = 0u; i < n.count; i++) {
      if (hit_triangle(ray, rs, bvh_index_at(n.first_or_left + i), none).kind != kPrimNone) return true;
    }
    if (top == 0u) return false;
    top--;
    n.first_or_left = bvh_pending_first(stack_node[top]);
    n.count = bvh_pending_count(stack_node[top]);
  }
  return false;
}

#endif  // PT_GPU_BVH_WALK_GLSL
