#pragma once
// Named, typed per-element attributes stored as one array per attribute (structure of arrays).
//
// A PropertyContainer holds the arrays for one element kind (vertices, halfedges, edges or
// faces); all its arrays always have the same length. A Property<H, T> is a cheap typed view
// that indexes one array with a handle of kind H. Views stay valid until the property is
// removed or the container is destroyed; copying a container deep-copies its arrays.
// `bool` is not allowed as T (std::vector<bool> has no references): use std::uint8_t.
#include <cassert>
#include <memory>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/handles.h"

namespace trilab {

/// A zero value for any attribute type: Eigen vectors are zeroed (their default
/// constructor leaves them uninitialized), everything else is value-initialized.
template <class T>
T zero_value() {
    if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>)
        return T::Zero();
    else
        return T{};
}

class BasePropertyArray {
public:
    explicit BasePropertyArray(std::string name) : name_(std::move(name)) {}
    virtual ~BasePropertyArray() = default;
    const std::string& name() const { return name_; }
    virtual const std::type_info& type() const = 0;
    virtual void reserve(std::size_t n) = 0;
    virtual void resize(std::size_t n) = 0;
    virtual void push_back() = 0;
    virtual void copy_element(std::size_t from, std::size_t to) = 0;
    virtual void swap_elements(std::size_t a, std::size_t b) = 0;
    /// Keeps element old_index[i] at position i, for i < old_index.size(), then shrinks.
    virtual void gather(const std::vector<Index>& old_index) = 0;
    virtual void shrink_to_fit() = 0;
    virtual std::unique_ptr<BasePropertyArray> clone() const = 0;

private:
    std::string name_;
};

template <class T>
class PropertyArray final : public BasePropertyArray {
    static_assert(!std::is_same_v<T, bool>, "use std::uint8_t instead of bool");

public:
    PropertyArray(std::string name, T default_value)
        : BasePropertyArray(std::move(name)), default_(std::move(default_value)) {}
    const std::type_info& type() const override { return typeid(T); }
    void reserve(std::size_t n) override { data_.reserve(n); }
    void resize(std::size_t n) override { data_.resize(n, default_); }
    void push_back() override { data_.push_back(default_); }
    void copy_element(std::size_t from, std::size_t to) override { data_[to] = data_[from]; }
    void swap_elements(std::size_t a, std::size_t b) override { std::swap(data_[a], data_[b]); }
    void gather(const std::vector<Index>& old_index) override {
        std::vector<T> out;
        out.reserve(old_index.size());
        for (Index i : old_index) out.push_back(std::move(data_[i]));
        data_ = std::move(out);
    }
    void shrink_to_fit() override { data_.shrink_to_fit(); }
    std::unique_ptr<BasePropertyArray> clone() const override {
        return std::make_unique<PropertyArray>(*this);
    }
    std::vector<T>& data() { return data_; }
    const std::vector<T>& data() const { return data_; }
    const T& default_value() const { return default_; }

private:
    std::vector<T> data_;
    T default_;
};

/// Typed view of one property array, indexed by handles of kind H.
template <class H, class T>
class Property {
public:
    Property() = default;
    explicit Property(PropertyArray<T>* array) : array_(array) {}
    explicit operator bool() const { return array_ != nullptr; }
    T& operator[](H h) {
        assert(array_ && h.idx() < array_->data().size());
        return array_->data()[h.idx()];
    }
    const T& operator[](H h) const {
        assert(array_ && h.idx() < array_->data().size());
        return array_->data()[h.idx()];
    }
    std::vector<T>& vector() { return array_->data(); }
    const std::vector<T>& vector() const { return array_->data(); }
    const std::string& name() const { return array_->name(); }

private:
    PropertyArray<T>* array_ = nullptr;
};

/// All property arrays of one element kind.
class PropertyContainer {
public:
    PropertyContainer() = default;
    PropertyContainer(const PropertyContainer& other) { *this = other; }
    PropertyContainer& operator=(const PropertyContainer& other) {
        if (this == &other) return *this;
        arrays_.clear();
        for (const auto& a : other.arrays_) arrays_.push_back(a->clone());
        size_ = other.size_;
        return *this;
    }
    PropertyContainer(PropertyContainer&&) noexcept = default;
    PropertyContainer& operator=(PropertyContainer&&) noexcept = default;

    std::size_t size() const { return size_; }
    std::size_t n_properties() const { return arrays_.size(); }

    /// Adds a new array; returns nullptr when a property of that name exists already.
    template <class T>
    PropertyArray<T>* add(const std::string& name, T default_value = zero_value<T>()) {
        if (find_base(name)) return nullptr;
        auto array = std::make_unique<PropertyArray<T>>(name, std::move(default_value));
        array->resize(size_);
        PropertyArray<T>* raw = array.get();
        arrays_.push_back(std::move(array));
        return raw;
    }
    /// The array of that name and type, or nullptr.
    template <class T>
    PropertyArray<T>* get(const std::string& name) const {
        BasePropertyArray* base = find_base(name);
        if (!base || base->type() != typeid(T)) return nullptr;
        return static_cast<PropertyArray<T>*>(base);
    }
    bool exists(const std::string& name) const { return find_base(name) != nullptr; }
    /// Removes the array of that name; returns whether one was removed.
    bool remove(const std::string& name) {
        for (auto it = arrays_.begin(); it != arrays_.end(); ++it) {
            if ((*it)->name() == name) {
                arrays_.erase(it);
                return true;
            }
        }
        return false;
    }
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& a : arrays_) out.push_back(a->name());
        return out;
    }

    void reserve(std::size_t n) {
        for (auto& a : arrays_) a->reserve(n);
    }
    void resize(std::size_t n) {
        for (auto& a : arrays_) a->resize(n);
        size_ = n;
    }
    void push_back() {
        for (auto& a : arrays_) a->push_back();
        ++size_;
    }
    void copy_element(std::size_t from, std::size_t to) {
        for (auto& a : arrays_) a->copy_element(from, to);
    }
    void swap_elements(std::size_t a, std::size_t b) {
        for (auto& arr : arrays_) arr->swap_elements(a, b);
    }
    void gather(const std::vector<Index>& old_index) {
        for (auto& a : arrays_) a->gather(old_index);
        size_ = old_index.size();
    }
    void shrink_to_fit() {
        for (auto& a : arrays_) a->shrink_to_fit();
    }
    void clear() {
        arrays_.clear();
        size_ = 0;
    }

private:
    BasePropertyArray* find_base(const std::string& name) const {
        for (const auto& a : arrays_)
            if (a->name() == name) return a.get();
        return nullptr;
    }
    std::vector<std::unique_ptr<BasePropertyArray>> arrays_;
    std::size_t size_ = 0;
};

}  // namespace trilab
