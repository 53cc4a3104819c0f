#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define SLAMKIT_NODE_POOL_ENABLED 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SLAMKIT_NODE_POOL_ENABLED 0
#endif
#endif
#ifndef SLAMKIT_NODE_POOL_ENABLED
#define SLAMKIT_NODE_POOL_ENABLED 1
#endif

namespace slamkit {

// Fixed-size blocks for the nodes of persistent trees (LandmarkTree), which a particle filter
// allocates and frees by the thousand per step from several threads.
//
// Why not malloc: glibc keeps freed small blocks in bins scattered over the heap and merges them
// whenever a larger request comes; reusing one then touches its neighbours as well. With a map of
// 10^5 landmarks the tree nodes span tens of megabytes, those touches miss the cache, and they cost
// more than the tree itself (FastSLAM's step grew 4× from 10^3 to 10^5 landmarks; 1.7× with this
// pool). A pool hands back the block freed last, touching only that block.
//
// A magazine allocator (Bonwick and Adams 2001): every thread keeps up to two chains of free
// blocks; a thread that frees more than it allocates (the one that resamples) passes whole chains
// to a shared depot, from which allocating threads refill, so memory follows the work between
// threads without walking the chains. Blocks return to the depot, never to the operating system:
// the pool holds the largest number of nodes alive at once. Built with AddressSanitizer the pool
// steps aside so that the sanitizer sees every node.
template <std::size_t kBytes, std::size_t kAlign>
class NodePool {
 public:
  static void* Allocate() {
    Cache& cache = LocalCache();
    if (cache.current.head == nullptr) cache.Refill();
    Block* block = cache.current.head;
    cache.current.head = block->next;
    --cache.current.count;
    return block;
  }

  static void Deallocate(void* p) noexcept {
    Cache& cache = LocalCache();
    auto* block = static_cast<Block*>(p);
    block->next = cache.current.head;
    cache.current.head = block;
    if (++cache.current.count == kChainBlocks) cache.Retire();
  }

 private:
  struct Block {
    Block* next;
  };
  static constexpr std::size_t kAlignment = kAlign < alignof(Block) ? alignof(Block) : kAlign;
  static constexpr std::size_t kStride =
      ((kBytes < sizeof(Block) ? sizeof(Block) : kBytes) + kAlignment - 1) / kAlignment *
      kAlignment;
  static constexpr std::size_t kChainBlocks = 1024;  // blocks per chain and per slab

  struct Chain {
    Block* head = nullptr;
    std::size_t count = 0;
  };

  // The shared chains of free blocks (slabs are never returned: see above).
  struct Depot {
    std::mutex mutex;
    std::vector<Chain> chains;

    void Put(Chain chain) {
      if (chain.head == nullptr) return;
      const std::lock_guard<std::mutex> lock(mutex);
      chains.push_back(chain);
    }
    Chain Take() {
      const std::lock_guard<std::mutex> lock(mutex);
      if (chains.empty()) return {};
      const Chain chain = chains.back();
      chains.pop_back();
      return chain;
    }
  };
  static Depot& SharedDepot() {
    static Depot* depot = new Depot;  // never destroyed: threads may free nodes during exit
    return *depot;
  }

  struct Cache {
    Chain current;
    Chain spare;  // a full chain, or none

    // `current` is full: it becomes the spare, and an older spare goes to the depot.
    void Retire() {
      SharedDepot().Put(spare);
      spare = current;
      current = {};
    }
    void Refill() {
      if (spare.head != nullptr) {
        current = spare;
        spare = {};
        return;
      }
      current = SharedDepot().Take();
      if (current.head == nullptr) current = {NewSlab(), kChainBlocks};
    }
    // A thread that ends gives its blocks to the others.
    ~Cache() {
      SharedDepot().Put(current);
      SharedDepot().Put(spare);
    }
  };
  static Cache& LocalCache() {
    thread_local Cache cache;
    return cache;
  }

  static Block* NewSlab() {
    auto* bytes = static_cast<std::byte*>(
        ::operator new(kStride* kChainBlocks, std::align_val_t(kAlignment)));
    Block* head = nullptr;
    for (std::size_t i = kChainBlocks; i-- > 0;) {
      auto* block = reinterpret_cast<Block*>(bytes + i * kStride);
      block->next = head;
      head = block;
    }
    return head;
  }
};

// The standard allocator interface over NodePool, for std::allocate_shared: single objects come
// from the pool of their size, arrays from operator new.
template <class T>
class NodePoolAllocator {
 public:
  using value_type = T;
  NodePoolAllocator() = default;
  template <class U>
  NodePoolAllocator(const NodePoolAllocator<U>& /*other*/) noexcept {}

  T* allocate(std::size_t n) {
    if (!SLAMKIT_NODE_POOL_ENABLED || n != 1) return std::allocator<T>().allocate(n);
    return static_cast<T*>(NodePool<sizeof(T), alignof(T)>::Allocate());
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (!SLAMKIT_NODE_POOL_ENABLED || n != 1) {
      std::allocator<T>().deallocate(p, n);
      return;
    }
    NodePool<sizeof(T), alignof(T)>::Deallocate(p);
  }

  template <class U>
  bool operator==(const NodePoolAllocator<U>& /*other*/) const noexcept {
    return true;
  }
};

}  // namespace slamkit
