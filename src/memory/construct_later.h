// An allocator for buffers whose elements are written whole right after they are made: pixel
// buffers that a clear fills on all threads, vertices prepared in ranges by the threads, triangle
// setups. std::vector's resize() and emplace_back() would first zero every element (a 16-byte
// pixel, a 160-byte vertex, a 296-byte setup), on the calling thread; with this allocator they
// leave it as allocated. The element types are implicit-lifetime (trivial, or aggregates), so
// their objects exist from allocation; whoever makes an element writes all of it before anything
// reads it. Everything else (assign, resize with a value, copies) works as with std::allocator.
// The memory comes from Base (the pixel buffers': PixelAllocator, pixel_memory.h).
#pragma once

#include <memory>
#include <new>
#include <utility>

namespace shadowref {

template <class T, class Base = std::allocator<T>>
struct ConstructLaterAllocator : Base {
  using Base::Base;
  template <class U>
  struct rebind {
    using other = ConstructLaterAllocator<U, typename std::allocator_traits<Base>::template rebind_alloc<U>>;
  };
  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace shadowref
