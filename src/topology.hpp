// Wires and rods as ordered chains of nodes with rest lengths per edge.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace slender {

struct Chain {
  std::string name;
  std::vector<int> nodes;           // node indices in order along the chain
  std::vector<double> rest_length;  // one per edge: nodes.size()-1, or nodes.size() if closed
  bool closed = false;

  int n_nodes() const { return static_cast<int>(nodes.size()); }
  int n_edges() const { return static_cast<int>(rest_length.size()); }
  // Edge e joins nodes[e] and nodes[(e+1) % n].
  int edge_head(int e) const { return nodes[(e + 1) % nodes.size()]; }
  int edge_tail(int e) const { return nodes[e]; }
  // Number of interior vertices that carry a bending spring.
  int n_hinges() const { return closed ? n_nodes() : (n_nodes() > 2 ? n_nodes() - 2 : 0); }
  // Hinge h joins edges (prev, next) around node `mid`.
  void hinge(int h, int& prev, int& mid, int& next) const {
    const int n = n_nodes();
    if (closed) {
      prev = nodes[(h - 1 + n) % n];
      mid = nodes[h];
      next = nodes[(h + 1) % n];
    } else {
      prev = nodes[h];
      mid = nodes[h + 1];
      next = nodes[h + 2];
    }
  }
  // Unwrapped chain position of hinge h's first node (prev); mid and next follow it. A
  // closed chain's hinge 0 starts at -1 (the positions of ChainForces, src/threads.hpp).
  long hinge_first_position(int h) const { return closed ? h - 1L : static_cast<long>(h); }
  // Growth at the start (injection): the new node becomes nodes[0].
  void grow_front(int node, double rest) {
    nodes.insert(nodes.begin(), node);
    rest_length.insert(rest_length.begin(), rest);
  }
  void grow_back(int node, double rest) {
    nodes.push_back(node);
    rest_length.push_back(rest);
  }
};

namespace shell {
struct GhostedMesh;
}

// A triangle mesh of a shell: its nodes are first_node + the mesh's local ids
// (real nodes, then ghosts); `reference` holds the unperturbed positions.
struct Surface {
  std::string name;
  std::shared_ptr<shell::GhostedMesh> mesh;
  int first_node = 0;
};

struct Topology {
  std::vector<Chain> chains;
  std::vector<Surface> surfaces;
  Surface* find_surface(const std::string& name) {
    for (auto& s : surfaces)
      if (s.name == name) return &s;
    return nullptr;
  }
  Chain* find(const std::string& name) {
    for (auto& c : chains)
      if (c.name == name) return &c;
    return nullptr;
  }
  int n_edges() const {
    int n = 0;
    for (auto& c : chains) n += c.n_edges();
    return n;
  }
  double min_rest_length() const {
    double m = 1e300;
    for (auto& c : chains)
      for (double l : c.rest_length) m = l < m ? l : m;
    return m;
  }
};

}  // namespace slender
