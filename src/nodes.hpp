// Node storage, structure of arrays. Position, velocity, force and mass always
// exist; every other per-node array is a typed property that a style requests by
// name when it is created, so a scene holds only what its styles need.
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

namespace slender {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;

template <class T>
struct PropertyTraits;
template <>
struct PropertyTraits<double> {
  static constexpr int ncomp = 1;
  static constexpr const char* name = "double";
  static double* data(double& v) { return &v; }
};
template <>
struct PropertyTraits<int> {
  static constexpr int ncomp = 1;
  static constexpr const char* name = "int";
};
template <>
struct PropertyTraits<Vec3> {
  static constexpr int ncomp = 3;
  static constexpr const char* name = "vec3";
  static double* data(Vec3& v) { return v.data(); }
};
template <>
struct PropertyTraits<Vec4> {
  static constexpr int ncomp = 4;
  static constexpr const char* name = "vec4";
  static double* data(Vec4& v) { return v.data(); }
};

struct PropertyOptions {
  bool restart = true;  // saved in checkpoints
  bool dump = false;    // written by dumps that ask for "all properties"
};

class PropertyBase {
 public:
  PropertyBase(std::string name, PropertyOptions opt) : name_(std::move(name)), opt_(opt) {}
  virtual ~PropertyBase() = default;
  const std::string& name() const { return name_; }
  const PropertyOptions& options() const { return opt_; }
  virtual const char* type_name() const = 0;
  virtual const std::type_info& type() const = 0;
  virtual int ncomp() const = 0;
  virtual void resize(size_t n) = 0;
  virtual size_t size() const = 0;
  virtual size_t bytes() const = 0;  // memory held by the values
  // Flat copies, ncomp values per node, for checkpoints and dumps.
  virtual std::vector<double> to_flat() const = 0;
  virtual void from_flat(const std::vector<double>& flat) = 0;
  // The guard's last good state: keep() copies the values aside (reusing the memory),
  // restore_kept() puts them back; false if nothing of this size was kept.
  virtual void keep() = 0;
  virtual bool restore_kept() = 0;

 private:
  std::string name_;
  PropertyOptions opt_;
};

template <class T>
class Property final : public PropertyBase {
 public:
  Property(std::string name, PropertyOptions opt, T init)
      : PropertyBase(std::move(name), opt), init_(init) {}
  const char* type_name() const override { return PropertyTraits<T>::name; }
  const std::type_info& type() const override { return typeid(T); }
  int ncomp() const override { return PropertyTraits<T>::ncomp; }
  void resize(size_t n) override { data_.resize(n, init_); }
  size_t size() const override { return data_.size(); }
  size_t bytes() const override { return data_.capacity() * sizeof(T); }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  std::vector<T>& values() { return data_; }
  std::vector<double> to_flat() const override {
    std::vector<double> out;
    out.reserve(data_.size() * ncomp());
    for (auto& v : data_) {
      if constexpr (std::is_same_v<T, int> || std::is_same_v<T, double>) {
        out.push_back(static_cast<double>(v));
      } else {
        for (int c = 0; c < ncomp(); ++c) out.push_back(v[c]);
      }
    }
    return out;
  }
  void keep() override {
    kept_ = data_;
    has_kept_ = true;
  }
  bool restore_kept() override {
    if (!has_kept_ || kept_.size() != data_.size()) return false;
    data_ = kept_;
    return true;
  }
  void from_flat(const std::vector<double>& flat) override {
    data_.resize(flat.size() / ncomp());
    for (size_t i = 0; i < data_.size(); ++i) {
      if constexpr (std::is_same_v<T, int>) {
        data_[i] = static_cast<int>(flat[i]);
      } else if constexpr (std::is_same_v<T, double>) {
        data_[i] = flat[i];
      } else {
        for (int c = 0; c < ncomp(); ++c) data_[i][c] = flat[i * ncomp() + c];
      }
    }
  }

 private:
  std::vector<T> kept_;
  bool has_kept_ = false;
  T init_;
  std::vector<T> data_;
};

class NodeStore {
 public:
  size_t size() const { return x.size(); }
  // Owned nodes come first; ghosts (periodic images or another rank's nodes)
  // follow. Serial, non-periodic scenes have no ghosts.
  size_t n_owned() const { return size() - n_ghost_; }
  size_t n_ghost() const { return n_ghost_; }

  // Appends a node and grows every allocated property; returns its index.
  size_t add(const Vec3& pos, double m) {
    x.push_back(pos);
    v.push_back(Vec3::Zero());
    f.push_back(Vec3::Zero());
    mass.push_back(m);
    for (auto& [k, p] : props_) p->resize(size());
    return size() - 1;
  }
  void resize(size_t n) {
    x.resize(n, Vec3::Zero());
    v.resize(n, Vec3::Zero());
    f.resize(n, Vec3::Zero());
    mass.resize(n, 1.0);
    for (auto& [k, p] : props_) p->resize(n);
  }

  // Returns the property, allocating it on first request. Asking again with
  // another type is a programming error between styles and throws.
  template <class T>
  Property<T>& require(const std::string& name, T init = T{}, PropertyOptions opt = {}) {
    auto it = props_.find(name);
    if (it != props_.end()) {
      if (it->second->type() != typeid(T))
        throw std::logic_error("node property '" + name + "' exists with type " +
                               it->second->type_name() + ", requested as " +
                               PropertyTraits<T>::name);
      return static_cast<Property<T>&>(*it->second);
    }
    auto p = std::make_unique<Property<T>>(name, opt, init);
    p->resize(size());
    auto& ref = *p;
    props_[name] = std::move(p);
    return ref;
  }
  template <class T>
  Property<T>* find(const std::string& name) {
    auto it = props_.find(name);
    if (it == props_.end() || it->second->type() != typeid(T)) return nullptr;
    return static_cast<Property<T>*>(it->second.get());
  }
  bool has(const std::string& name) const { return props_.count(name) > 0; }
  PropertyBase* find_any(const std::string& name) {
    auto it = props_.find(name);
    return it == props_.end() ? nullptr : it->second.get();
  }
  // Names of every array the scene holds: the four core arrays, then properties.
  std::vector<std::string> property_names() const {
    std::vector<std::string> out{"position", "velocity", "force", "mass"};
    for (auto& [k, p] : props_) out.push_back(k);
    return out;
  }
  const std::map<std::string, std::unique_ptr<PropertyBase>>& properties() const { return props_; }

  std::vector<Vec3> x, v, f;
  std::vector<double> mass;

 private:
  size_t n_ghost_ = 0;
  std::map<std::string, std::unique_ptr<PropertyBase>> props_;
};

}  // namespace slender
