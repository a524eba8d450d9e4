// caoBoxTree.h - the bounding-volume hierarchy the ray-traced reference's
// scenes share (triangles: Surface/caoTriangleBVH.h; capsules:
// Lines/caoCapsules.h), in double precision end to end: items split at the
// median of their centres along the centres' widest axis, leaves of at most
// LeafSize items; a leaf's box grown from its items' boxes, an inner node's
// from its children's (no level reads the items again). While threads are
// left, a node's right half is built on a thread of its own, into a
// separate node list joined in the serial build's order: the tree is the
// same node for node whatever the thread count. The traversal
// visits the leaves a ray's slab test admits, nearest bound first not
// required: each visitor keeps the best distance found so far.
#ifndef caoBoxTree_h
#define caoBoxTree_h

#include "caoMemory.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <limits>
#include <system_error>
#include <thread>
#include <vector>

namespace cao
{

/// Room for `n` elements, its pages advised to huge pages before the first
/// write (caoMemory.h: on the development VM each 4 KiB page's first touch
/// is a fault of about 12 us).
template <class T>
void ReserveHuge(std::vector<T>& v, std::size_t n)
{
  v.reserve(n);
  AdviseHugePages(v.data(), n * sizeof(T));
}

class BoxTree
{
public:
  /// An item while the tree is built: its centre and its input index. The
  /// build sorts them in place into leaf order: slot s holds items[s].id.
  struct Item
  {
    double c[3];
    std::int64_t id;
  };
  static constexpr int LeafSize = 4;
  static constexpr int MaximumDepth = 64;

  /// Builds over `items` (reordered into leaf order); box(id, lo, hi) grows
  /// lo and hi (3 each) by item id's box, and may be called from several
  /// threads at once. `threads`: at most so many at once (0: the
  /// hardware's); the tree does not depend on it.
  template <class Box>
  void Build(std::vector<Item>& items, Box box, int threads = 0)
  {
    this->nodes.clear();
    if (items.empty())
      return;
    // A node of 5 or more items splits in two halves of at least 2, so a
    // leaf holds at least 2 (one only when there is one): fewer nodes than
    // items.
    ReserveHuge(this->nodes, items.size() + 1);
    const unsigned n = threads > 0 ? static_cast<unsigned>(threads) : std::thread::hardware_concurrency();
    BuildNode(this->nodes, items, box, 0, static_cast<std::int64_t>(items.size()), 0,
      static_cast<int>(std::max(1u, std::min(n, 1024u))));
  }

  /// Calls leaf(first, count, best) for every leaf whose box a ray
  /// (origin + t direction) crosses with t in [tMin, best]; the visitor
  /// may lower `best` (its closest hit so far) and returns true to stop
  /// (an any-hit query found one). Returns whether a visitor stopped it.
  template <class Leaf>
  bool Traverse(const double origin[3], const double direction[3], double tMin, double& best,
    Leaf leaf) const
  {
    if (this->nodes.empty())
      return false;
    double inverse[3];
    for (int d = 0; d < 3; ++d)
      inverse[d] = 1.0 / direction[d]; // +-inf for a zero component: its slab is unbounded
    std::int64_t stack[2 * MaximumDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& node = this->nodes[static_cast<std::size_t>(stack[--top])];
      double enter = tMin, exit = best;
      for (int d = 0; d < 3; ++d)
      {
        const double a = (node.lo[d] - origin[d]) * inverse[d];
        const double b = (node.hi[d] - origin[d]) * inverse[d];
        // NaN (0 * inf, the origin on the slab's plane) compares false and
        // is ignored: the slab does not bound the ray there (conservative).
        const double near = a < b ? a : b, far = a < b ? b : a;
        if (near > enter)
          enter = near;
        if (far < exit)
          exit = far;
      }
      if (enter > exit)
        continue; // (a box reaching exactly `best` is still visited: ties)
      if (node.count == 0)
      {
        const std::int64_t self = &node - this->nodes.data();
        stack[top++] = node.first;
        stack[top++] = self + 1;
        continue;
      }
      if (leaf(node.first, static_cast<std::int64_t>(node.count), best))
        return true;
    }
    return false;
  }

  /// Calls leaf(first, count, best2) for every leaf whose box lies within
  /// sqrt(best2) of `point`; the visitor may lower `best2` (its nearest
  /// item's squared distance so far).
  template <class Leaf>
  void TraverseNear(const double point[3], double& best2, Leaf leaf) const
  {
    if (this->nodes.empty())
      return;
    std::int64_t stack[2 * MaximumDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& node = this->nodes[static_cast<std::size_t>(stack[--top])];
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        const double below = node.lo[d] - point[d], above = point[d] - node.hi[d];
        const double gap = below > 0.0 ? below : above > 0.0 ? above : 0.0;
        d2 += gap * gap;
      }
      if (!(d2 <= best2))
        continue;
      if (node.count == 0)
      {
        const std::int64_t self = &node - this->nodes.data();
        stack[top++] = node.first;
        stack[top++] = self + 1;
        continue;
      }
      leaf(node.first, static_cast<std::int64_t>(node.count), best2);
    }
  }

  void Clear() { this->nodes.clear(); }
  /// Whether `other` holds the same nodes, bit for bit, in the same order.
  bool SameNodes(const BoxTree& other) const
  {
    return this->nodes.size() == other.nodes.size() &&
      std::equal(this->nodes.begin(), this->nodes.end(), other.nodes.begin(), [](const Node& a, const Node& b) {
        return std::equal(a.lo, a.lo + 3, b.lo) && std::equal(a.hi, a.hi + 3, b.hi) && a.first == b.first &&
          a.count == b.count;
      });
  }
  bool Empty() const { return this->nodes.empty(); }
  std::int64_t NumberOfNodes() const { return static_cast<std::int64_t>(this->nodes.size()); }
  /// The root's box (xmin, xmax, ...); inverted when empty.
  std::array<double, 6> Bounds() const
  {
    if (this->nodes.empty())
      return { { 1, -1, 1, -1, 1, -1 } };
    const Node& root = this->nodes[0];
    return { { root.lo[0], root.hi[0], root.lo[1], root.hi[1], root.lo[2], root.hi[2] } };
  }

private:
  struct Node
  {
    double lo[3], hi[3];
    std::int64_t first; ///< leaf: first slot; inner: right child (left is next)
    std::int32_t count; ///< leaf: items; inner: 0
  };

  /// Halves smaller than this are built on their parent's thread.
  static constexpr std::int64_t ParallelItems = 1 << 14;

  /// The subtree of items [begin, end) appended to `nodes` in depth-first
  /// order (a node, its left subtree, its right one): its root's index; on
  /// at most `budget` threads at once (this one included).
  template <class Box>
  static std::int64_t BuildNode(std::vector<Node>& nodes, std::vector<Item>& items, Box& box, std::int64_t begin,
    std::int64_t end, int depth, int budget)
  {
    const std::int64_t index = static_cast<std::int64_t>(nodes.size());
    nodes.push_back(Node{});
    Node node;
    double clo[3], chi[3];
    for (int d = 0; d < 3; ++d)
    {
      node.lo[d] = clo[d] = std::numeric_limits<double>::infinity();
      node.hi[d] = chi[d] = -std::numeric_limits<double>::infinity();
    }
    for (std::int64_t i = begin; i < end; ++i)
      for (int d = 0; d < 3; ++d)
      {
        clo[d] = std::min(clo[d], items[static_cast<std::size_t>(i)].c[d]);
        chi[d] = std::max(chi[d], items[static_cast<std::size_t>(i)].c[d]);
      }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (chi[d] - clo[d] > chi[axis] - clo[axis])
        axis = d;
    const std::int64_t count = end - begin;
    if (count <= LeafSize || depth >= MaximumDepth || !(chi[axis] > clo[axis]))
    {
      for (std::int64_t i = begin; i < end; ++i)
        box(items[static_cast<std::size_t>(i)].id, node.lo, node.hi);
      node.first = begin;
      node.count = static_cast<std::int32_t>(count);
      nodes[static_cast<std::size_t>(index)] = node;
      return index;
    }
    const std::int64_t middle = begin + count / 2;
    std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end,
      [axis](const Item& a, const Item& b) { return a.c[axis] < b.c[axis]; });
    std::int64_t left = 0, right = 0;
    bool built = false;
    if (budget > 1 && count >= 2 * ParallelItems)
    {
      // The right half on its own thread into its own list (its indices
      // from 0), appended after the left half: the serial order. An
      // exception on either side (memory) reaches the caller after the join.
      std::vector<Node> half;
      std::exception_ptr failed;
      std::thread worker;
      try
      {
        worker = std::thread([&]() {
          try
          {
            BuildNode(half, items, box, middle, end, depth + 1, budget - budget / 2);
          }
          catch (...)
          {
            failed = std::current_exception();
          }
        });
      }
      catch (const std::system_error&)
      {
        // No thread to be had: the serial build below.
      }
      if (worker.joinable())
      {
        try
        {
          left = BuildNode(nodes, items, box, begin, middle, depth + 1, budget / 2);
        }
        catch (...)
        {
          worker.join();
          throw;
        }
        worker.join();
        if (failed)
          std::rethrow_exception(failed);
        right = static_cast<std::int64_t>(nodes.size());
        for (Node h : half)
        {
          if (h.count == 0)
            h.first += right; // an inner node's right child; a leaf's first slot stays
          nodes.push_back(h);
        }
        built = true;
      }
    }
    if (!built)
    {
      left = BuildNode(nodes, items, box, begin, middle, depth + 1, 1);
      right = BuildNode(nodes, items, box, middle, end, depth + 1, 1);
    }
    for (int d = 0; d < 3; ++d)
    {
      const Node& l = nodes[static_cast<std::size_t>(left)];
      const Node& r = nodes[static_cast<std::size_t>(right)];
      node.lo[d] = std::min(l.lo[d], r.lo[d]);
      node.hi[d] = std::max(l.hi[d], r.hi[d]);
    }
    node.first = right;
    node.count = 0;
    nodes[static_cast<std::size_t>(index)] = node;
    return index;
  }

  std::vector<Node> nodes;
};

}

#endif
