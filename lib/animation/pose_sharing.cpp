#include "animation/pose_sharing.h"

#include <stdexcept>

namespace crowdprof {

namespace {
// SplitMix64's finaliser: every bit of the key moves the slot.
size_t mix(uint64_t key) {
  key ^= key >> 30;
  key *= 0xbf58476d1ce4e5b9ull;
  key ^= key >> 27;
  key *= 0x94d049bb133111ebull;
  key ^= key >> 31;
  return static_cast<size_t>(key);
}
}  // namespace

void PoseSharing::reset(std::span<const uint16_t> kind_of_copy, size_t kinds) {
  size_t n = kind_of_copy.size();
  shown_.resize(n);
  refs_.assign(n, 1);
  key_.assign(n, kNoState);
  kind_.assign(kind_of_copy.begin(), kind_of_copy.end());
  prev_.assign(n, kNone);
  next_.assign(n, kNone);
  head_.assign(kinds, kNone);
  tail_.assign(kinds, kNone);
  for (size_t i = 0; i < n; ++i) shown_[i] = static_cast<uint32_t>(i);
  size_t slots = 16;
  while (slots < 2 * n + 2) slots *= 2;
  table_keys_.assign(slots, kNoState);
  table_storage_.assign(slots, kNone);
  mask_ = slots - 1;
  last_taken_ = kNone;
}

size_t PoseSharing::slot_of(uint64_t key) const {
  size_t slot = mix(key) & mask_;
  while (table_keys_[slot] != key && table_keys_[slot] != kNoState) slot = (slot + 1) & mask_;
  return slot;
}

void PoseSharing::insert(uint64_t key, uint32_t storage) {
  size_t slot = slot_of(key);
  table_keys_[slot] = key;
  table_storage_[slot] = storage;
}

void PoseSharing::erase(uint64_t key) {
  size_t hole = slot_of(key);
  if (table_keys_[hole] != key) return;
  // Backward-shift deletion: entries after the hole that could live in it move
  // up, so that lookups never meet a gap before their key.
  for (size_t next = (hole + 1) & mask_; table_keys_[next] != kNoState; next = (next + 1) & mask_) {
    size_t home = mix(table_keys_[next]) & mask_;
    bool movable = hole <= next ? (home <= hole || home > next) : (home <= hole && home > next);
    if (!movable) continue;
    table_keys_[hole] = table_keys_[next];
    table_storage_[hole] = table_storage_[next];
    hole = next;
  }
  table_keys_[hole] = kNoState;
  table_storage_[hole] = kNone;
}

void PoseSharing::unlink(uint32_t s) {
  uint16_t k = kind_[s];
  (prev_[s] == kNone ? head_[k] : next_[prev_[s]]) = next_[s];
  (next_[s] == kNone ? tail_[k] : prev_[next_[s]]) = prev_[s];
  prev_[s] = next_[s] = kNone;
}

void PoseSharing::push_back(uint32_t s) {
  uint16_t k = kind_[s];
  prev_[s] = tail_[k];
  next_[s] = kNone;
  (tail_[k] == kNone ? head_[k] : next_[tail_[k]]) = s;
  tail_[k] = s;
}

void PoseSharing::free_storage(uint32_t s) {
  if (key_[s] == kNoState) {
    // The rest pose is never looked up again: its storage is free at once,
    // ahead of those that still hold a state.
    prev_[s] = kNone;
    next_[s] = head_[kind_[s]];
    (head_[kind_[s]] == kNone ? tail_[kind_[s]] : prev_[head_[kind_[s]]]) = s;
    head_[kind_[s]] = s;
    return;
  }
  push_back(s);
}

uint32_t PoseSharing::take_slow(size_t copy, uint64_t key, bool* evaluate) {
  size_t slot = slot_of(key);
  uint32_t s;
  if (table_keys_[slot] == key) {
    s = table_storage_[slot];
    if (refs_[s] == 0) unlink(s);
    *evaluate = false;
  } else {
    s = head_[kind_[copy]];
    // Each copy shows one storage, and a character has one per copy: one that
    // released its storage before taking a new one always finds room.
    if (s == kNone) throw std::logic_error("PoseSharing::take without a release");
    unlink(s);
    if (key_[s] != kNoState) erase(key_[s]);
    key_[s] = key;
    insert(key, s);
    *evaluate = true;
  }
  ++refs_[s];
  shown_[copy] = s;
  last_taken_ = s;
  return s;
}

}  // namespace crowdprof
