// Animation sharing (issue 13): which copy's pose storage holds each state
// (character, action, time) a copy shows, so that copies in the same state
// share one pose evaluation and one skinned mesh.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace crowdprof {

// A state as a 64-bit key: character, action and the bits of the time sampled.
inline uint64_t state_key(uint16_t kind, uint16_t action, uint32_t time_bits) {
  return (uint64_t{kind} << 48) | (uint64_t{action} << 32) | time_bits;
}

// Storages are the copies' own pose storage (palette, skinned mesh): storage
// s belongs to character kind_of(s) and may hold any state of that character.
// Each copy shows one storage; a storage that no copy shows keeps its state
// (a later copy in that state takes it without evaluating it again) until a
// new state needs the room: the one released longest ago of its character goes.
// There is always room: a character has as many storages as copies, and each
// copy shows one.
//
// Plain data and one pass per frame; nothing allocates after reset().
class PoseSharing {
 public:
  // One storage per copy; copy i starts showing storage i, which holds no
  // state (the rest pose). Allocates.
  void reset(std::span<const uint16_t> kind_of_copy, size_t kinds);

  // The storage copy `copy` shows.
  uint32_t shown(size_t copy) const { return shown_[copy]; }
  // The storage each copy shows.
  std::span<const uint32_t> shown_storages() const { return shown_; }
  // How many copies show storage s.
  uint32_t viewers(uint32_t storage) const { return refs_[storage]; }

  // Copy `copy` stops showing its storage (call for every copy that changes
  // state this frame before any take()).
  void release(size_t copy) {
    uint32_t s = shown_[copy];
    if (--refs_[s] == 0) free_storage(s);
  }
  // Copy `copy` shows `key` from now on. Returns the storage holding it; sets
  // *evaluate when the caller must evaluate the state into it (it was not held).
  uint32_t take(size_t copy, uint64_t key, bool* evaluate) {
    // Copies in one state come one after another (a shared action: all of
    // them), so the storage of the last take answers most takes at once. A key
    // is held by one storage at most: key_[s] == key is the table's answer.
    uint32_t s = last_taken_;
    if (s == kNone || key_[s] != key || refs_[s] == 0) return take_slow(copy, key, evaluate);
    ++refs_[s];
    shown_[copy] = s;
    *evaluate = false;
    return s;
  }
  // release() and take() for many copies, in order, as the frame loop calls
  // them: copies that show one storage one after another give it up at once,
  // and copies that take one key one after another are counted in at once (a
  // storage's count is then not read back and written per copy).
  void release(std::span<const uint32_t> copies);
  // Every copy of `copies` (not empty) shows `key` from now on.
  uint32_t take(std::span<const uint32_t> copies, uint64_t key, bool* evaluate);
  // The key a storage holds (kNoState for the rest pose).
  uint64_t key_of(uint32_t storage) const { return key_[storage]; }
  static constexpr uint64_t kNoState = ~uint64_t{0};

 private:
  // A storage no copy shows any more joins its character's free list.
  void free_storage(uint32_t storage);
  uint32_t take_slow(size_t copy, uint64_t key, bool* evaluate);
  // Open addressing with linear probing, 2^k slots for at least twice the
  // storages; kNoState marks an empty slot.
  size_t slot_of(uint64_t key) const;
  void erase(uint64_t key);
  void insert(uint64_t key, uint32_t storage);
  // The storages no copy shows, per character, oldest release first (a
  // doubly-linked list through prev_/next_; kNone ends it).
  void unlink(uint32_t storage);
  void push_back(uint32_t storage);
  static constexpr uint32_t kNone = ~uint32_t{0};

  std::vector<uint32_t> shown_, refs_;
  std::vector<uint64_t> key_;
  std::vector<uint16_t> kind_;
  std::vector<uint32_t> prev_, next_, head_, tail_;  // head_/tail_ per character
  std::vector<uint64_t> table_keys_;
  std::vector<uint32_t> table_storage_;
  size_t mask_ = 0;
  uint32_t last_taken_ = kNone;  // the storage the last take() returned
};

}  // namespace crowdprof
