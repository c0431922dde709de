// foglab — what every file that uses FFTW shares: the one lock around its
// planner, and fftw_malloc'd arrays.
//
// FFTW's planner and fftw_destroy_plan are not thread-safe (executing a plan
// with the new-array functions is). Every file that plans FFTs (psd.cc,
// theo1_kernel.cc) takes this mutex around planning and destruction, so
// that they may run in parallel with each other.
#pragma once

#include <fftw3.h>

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <new>

namespace foglab::stats::detail {

std::mutex& fftw_planner_mutex();

/// An array from fftw_malloc (all equally aligned; at least one element),
/// freed on scope exit, also during unwinding.
template <typename T>
class FftwArray {
 public:
  explicit FftwArray(std::size_t count)
      : data_(static_cast<T*>(fftw_malloc(sizeof(T) * std::max<std::size_t>(count, 1)))) {
    if (data_ == nullptr) throw std::bad_alloc();
  }
  FftwArray(FftwArray&& other) noexcept : data_(other.data_) { other.data_ = nullptr; }
  FftwArray(const FftwArray&) = delete;
  FftwArray& operator=(const FftwArray&) = delete;
  FftwArray& operator=(FftwArray&&) = delete;
  ~FftwArray() { fftw_free(data_); }
  T* get() const { return data_; }

 private:
  T* data_;
};

}  // namespace foglab::stats::detail
