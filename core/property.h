#pragma once
// Named, typed per-element attributes stored as one array per attribute (structure of arrays).
//
// A PropertyContainer holds the arrays for one element kind (vertices, halfedges, edges or
// faces); all its arrays always have the same length. A Property<H, T> is a cheap typed view
// that indexes one array with a handle of kind H; Property<H, const T> is a read-only view
// (what a const mesh hands out). Views stay valid until the property is removed or the
// container is destroyed.
//
// Copy-on-write: copying a container shares its arrays' values; the first write access to a
// shared array (a mutable view's operator[] or vector(), or any resizing) copies it first. So
// a copy of a mesh costs one pointer per array, and copies that change only the positions
// (a smoothing step, a history snapshot) share every other array by construction. Reading
// never copies, so const objects may be read from several threads while the owner of another
// copy writes to its own.
//
// Revisions: every array has a revision, a number that changes whenever its values may have
// changed (a write access, as above) and that copies share with the values they share. Equal
// revisions mean equal values; the converse need not hold. Numbers are drawn lazily, when a
// revision is asked for, from one process-wide increasing counter, so a number drawn later is
// larger than every number drawn before: the largest revision of a set of arrays therefore
// identifies the values of the whole set (HalfedgeMesh::revision()). A reference into an
// array's values, once taken, must not be written through after its revision was read.
// `bool` is not allowed as T (std::vector<bool> has no references): use std::uint8_t.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdint>
#include <cstring>
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

template <class T>
struct is_handle : std::false_type {};
template <class Tag>
struct is_handle<Handle<Tag>> : std::true_type {};

/// Whether arrays of T can be compared bit for bit with memcmp (no padding bytes): numbers,
/// fixed-size Eigen vectors of numbers, and the one-index handle types.
template <class T>
constexpr bool is_bitwise_comparable() {
    if constexpr (std::is_arithmetic_v<T>)
        return true;
    else if constexpr (std::is_base_of_v<Eigen::MatrixBase<T>, T>)
        return T::SizeAtCompileTime > 0 &&
               sizeof(T) == std::size_t(T::SizeAtCompileTime) * sizeof(typename T::Scalar);
    else
        return is_handle<T>::value;
}

/// The next number of the process-wide revision counter (never 0, never repeated).
inline std::uint64_t draw_revision() {
    static std::atomic<std::uint64_t> counter{0};
    return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

/// A revision drawn lazily: touch() marks a change, get() draws a number for the first request
/// after it (threads asking at once agree on one number).
class LazyRevision {
public:
    LazyRevision() = default;
    /// A copy has the same number (drawn first when the original has none yet), so copies of
    /// the same values agree.
    LazyRevision(const LazyRevision& other) noexcept : value_(other.get()) {}
    LazyRevision& operator=(const LazyRevision& other) noexcept {
        value_.store(other.get(), std::memory_order_relaxed);
        return *this;
    }
    void touch() { value_.store(0, std::memory_order_relaxed); }
    std::uint64_t get() const {
        std::uint64_t v = value_.load(std::memory_order_relaxed);
        if (v == 0) {
            const std::uint64_t fresh = draw_revision();
            v = value_.compare_exchange_strong(v, fresh, std::memory_order_relaxed) ? fresh : v;
        }
        return v;
    }

private:
    mutable std::atomic<std::uint64_t> value_{0};
};

class BasePropertyArray {
public:
    explicit BasePropertyArray(std::string name) : name_(std::move(name)) {}
    BasePropertyArray(const BasePropertyArray&) = default;
    BasePropertyArray& operator=(const BasePropertyArray&) = delete;
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
    /// A new array of the same name sharing these values (copy-on-write).
    virtual std::unique_ptr<BasePropertyArray> clone() const = 0;
    /// Identifies the stored values: equal for arrays that share them.
    virtual const void* values_id() const = 0;
    /// Bytes of the stored values (size x element size).
    virtual std::size_t bytes() const = 0;
    /// Shares `other`'s values when it has the same type and equal values bit for bit (only
    /// for is_bitwise_comparable types); returns whether it does now.
    virtual bool share_if_equal(const BasePropertyArray& other) = 0;
    /// Changes whenever the values may have changed; shared with copies (see the file comment).
    std::uint64_t revision() const { return revision_.get(); }

protected:
    void touch() { revision_.touch(); }

private:
    std::string name_;
    LazyRevision revision_;
};

template <class T>
class PropertyArray final : public BasePropertyArray {
    static_assert(!std::is_same_v<T, bool>, "use std::uint8_t instead of bool");

public:
    PropertyArray(std::string name, T default_value)
        : BasePropertyArray(std::move(name)),
          values_(std::make_shared<std::vector<T>>()),
          default_(std::move(default_value)) {}
    const std::type_info& type() const override { return typeid(T); }
    void reserve(std::size_t n) override {
        if (n > values_->capacity()) data().reserve(n);
    }
    void resize(std::size_t n) override {
        if (n != values_->size()) data().resize(n, default_);
    }
    void push_back() override { data().push_back(default_); }
    void copy_element(std::size_t from, std::size_t to) override {
        std::vector<T>& d = data();
        d[to] = d[from];
    }
    void swap_elements(std::size_t a, std::size_t b) override {
        std::vector<T>& d = data();
        std::swap(d[a], d[b]);
    }
    void gather(const std::vector<Index>& old_index) override {
        gather_mapped(old_index, [](const T& x) -> const T& { return x; });
    }
    /// gather() with every kept value passed through `map` (one pass: renumbering links).
    template <class Map>
    void gather_mapped(const std::vector<Index>& old_index, const Map& map) {
        auto out = std::make_shared<std::vector<T>>(old_index.size());
        const T* in = values_->data();
        T* to = out->data();
        const Index* from = old_index.data();
        for (std::size_t i = 0, n = old_index.size(); i < n; ++i) to[i] = map(in[from[i]]);
        values_ = std::move(out);
        touch();
    }
    void shrink_to_fit() override {
        if (values_.use_count() == 1) values_->shrink_to_fit();  // a shared copy is tight
    }
    std::unique_ptr<BasePropertyArray> clone() const override {
        return std::make_unique<PropertyArray>(*this);
    }
    const void* values_id() const override { return values_.get(); }
    std::size_t bytes() const override { return values_->size() * sizeof(T); }
    bool share_if_equal(const BasePropertyArray& other) override {
        if constexpr (is_bitwise_comparable<T>()) {
            if (other.type() != typeid(T)) return false;
            const auto& o = static_cast<const PropertyArray&>(other);
            if (o.values_ == values_) return true;
            const std::vector<T>& a = *values_;
            const std::vector<T>& b = *o.values_;
            if (a.size() != b.size() ||
                (!a.empty() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) != 0))
                return false;
            values_ = o.values_;
            return true;
        } else {
            (void)other;
            return false;
        }
    }
    /// The values for writing: copied first when shared with another array. Inline: every
    /// write through a mutable view comes here (the copy is out of line, unshare()).
    std::vector<T>& data() {
        if (values_.use_count() != 1) unshare();
        touch();
        return *values_;
    }
    const std::vector<T>& data() const { return *values_; }
    /// Replaces the values without copying the old ones.
    void assign(std::vector<T> values) {
        values_ = std::make_shared<std::vector<T>>(std::move(values));
        touch();
    }
    const T& default_value() const { return default_; }

private:
    // Gives this array its own copy of the shared values (the cold path of data()).
    [[gnu::noinline]] void unshare() { values_ = std::make_shared<std::vector<T>>(*values_); }

    std::shared_ptr<std::vector<T>> values_;
    T default_;
};

/// Typed view of one property array, indexed by handles of kind H; with a const T, a
/// read-only view. A mutable view's operator[] and vector() are write accesses (see the
/// file comment); read through a const view (or std::as_const) where nothing is written.
template <class H, class T>
class Property {
    using Value = std::remove_const_t<T>;
    using Array =
        std::conditional_t<std::is_const_v<T>, const PropertyArray<Value>, PropertyArray<Value>>;

public:
    Property() = default;
    explicit Property(Array* array) : array_(array) {}
    /// A mutable view converts to a read-only one.
    template <class U, class = std::enable_if_t<std::is_const_v<T> && std::is_same_v<U, Value>>>
    Property(const Property<H, U>& other) : array_(other.array()) {}
    explicit operator bool() const { return array_ != nullptr; }
    T& operator[](H h) {
        assert(array_ && h.idx() < array_->data().size());
        return array_->data()[h.idx()];
    }
    const Value& operator[](H h) const {
        assert(array_ && h.idx() < std::as_const(*array_).data().size());
        return std::as_const(*array_).data()[h.idx()];
    }
    std::conditional_t<std::is_const_v<T>, const std::vector<Value>&, std::vector<Value>&>
    vector() {
        return array_->data();
    }
    const std::vector<Value>& vector() const { return std::as_const(*array_).data(); }
    const std::string& name() const { return array_->name(); }
    Array* array() const { return array_; }

private:
    Array* array_ = nullptr;
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
        layout_revision_ = other.layout_revision_;
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
    PropertyArray<T>* get(const std::string& name) {
        BasePropertyArray* base = find_base(name);
        if (!base || base->type() != typeid(T)) return nullptr;
        return static_cast<PropertyArray<T>*>(base);
    }
    template <class T>
    const PropertyArray<T>* get(const std::string& name) const {
        const BasePropertyArray* base = find_base(name);
        if (!base || base->type() != typeid(T)) return nullptr;
        return static_cast<const PropertyArray<T>*>(base);
    }
    bool exists(const std::string& name) const { return find_base(name) != nullptr; }
    /// Removes the array of that name; returns whether one was removed.
    bool remove(const std::string& name) {
        for (auto it = arrays_.begin(); it != arrays_.end(); ++it) {
            if ((*it)->name() == name) {
                arrays_.erase(it);
                layout_revision_.touch();
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
    /// resize() in pieces, for a caller that resizes the arrays of several containers at once
    /// on several threads (HalfedgeMesh::resize_elements()): resize_array(k, n) for every k
    /// below n_properties() (each on any thread, no two on the same k at once), then
    /// set_size(n).
    void resize_array(std::size_t k, std::size_t n) { arrays_[k]->resize(n); }
    void set_size(std::size_t n) { size_ = n; }
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
    /// gather() of every array but those `skip(array)` accepts, which the caller gathers itself
    /// (PropertyArray::gather_mapped(), possibly on another thread: this touches none of them).
    template <class Skip>
    void gather_except(const std::vector<Index>& old_index, const Skip& skip) {
        for (auto& a : arrays_)
            if (!skip(a.get())) a->gather(old_index);
        size_ = old_index.size();
    }
    void shrink_to_fit() {
        for (auto& a : arrays_) a->shrink_to_fit();
    }
    void clear() {
        arrays_.clear();
        size_ = 0;
        layout_revision_.touch();
    }

    /// Changes when an array is removed (an added array brings a revision of its own).
    std::uint64_t layout_revision() const { return layout_revision_.get(); }
    /// The largest revision of the arrays whose name `include(name)` accepts (0: none).
    template <class Include>
    std::uint64_t max_revision(Include&& include) const {
        std::uint64_t r = 0;
        for (const auto& a : arrays_)
            if (include(a->name())) r = std::max(r, a->revision());
        return r;
    }
    /// Calls f(name, values_id, bytes) for every array (see BasePropertyArray).
    template <class F>
    void for_each_array(F&& f) const {
        for (const auto& a : arrays_) f(a->name(), a->values_id(), a->bytes());
    }
    /// Shares the values of `other`'s array of the same name wherever they are equal bit for
    /// bit (BasePropertyArray::share_if_equal); returns how many arrays are shared now.
    std::size_t share_equal_arrays(const PropertyContainer& other) {
        std::size_t shared = 0;
        for (auto& a : arrays_)
            if (const BasePropertyArray* b = other.find_base(a->name()))
                shared += a->share_if_equal(*b) ? 1 : 0;
        return shared;
    }

private:
    BasePropertyArray* find_base(const std::string& name) const {
        for (const auto& a : arrays_)
            if (a->name() == name) return a.get();
        return nullptr;
    }
    std::vector<std::unique_ptr<BasePropertyArray>> arrays_;
    std::size_t size_ = 0;
    LazyRevision layout_revision_;
};

}  // namespace trilab
