// Per-pair history (friction springs, the side a contact was made from) carried from
// one pair list to the next: the one way every contact pair list keeps its history
// (node-edge, segment-segment, shell triangle pairs; a wall's contact is one per node and
// lives in a node property). Pairs are matched by node ids (triangle ids for shells),
// never by positions in the edge list: a chain that grows at its front (injection) renumbers every
// edge, and matching by edge number handed each contact's history to the neighbouring edge — across
// a hairpin the remembered side then looked crossed and the "push back" force blew the wire apart
// (2D crumpling, f = 50).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace slender {

// A key of two ids, nodes or triangles (unordered when `symmetric`).
inline std::uint64_t id_pair_key(int a, int b, bool symmetric = false) {
  if (symmetric && b < a) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// For every index k of a new list (size n_now) whose key_now(k) matches an index of
// the old list (size n_old) that has history (has_old(k)), copy(old index, new index).
// Only entries with history go into the lookup, so a rebuild costs little more than
// before. For lists whose history lives beside the entries (structure of arrays).
template <class KeyOld, class KeyNow, class Has, class Copy>
void carry_pair_history_indexed(std::size_t n_old, std::size_t n_now, KeyOld key_old,
                                KeyNow key_now, Has has_old, Copy copy) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t k = 0; k < n_old; ++k)
    if (has_old(k)) index.emplace(key_old(k), k);
  if (index.empty()) return;
  for (std::size_t k = 0; k < n_now; ++k)
    if (auto it = index.find(key_now(k)); it != index.end()) copy(it->second, k);
}

// The same for lists of entries that hold their history: for every entry of `now`
// whose key(entry) matches an entry of `old` with history, copy(old entry, new entry).
template <class Entry, class Key, class Has, class Copy>
void carry_pair_history(const std::vector<Entry>& old, std::vector<Entry>& now, Key key, Has has,
                        Copy copy) {
  carry_pair_history_indexed(
      old.size(), now.size(), [&](std::size_t k) { return key(old[k]); },
      [&](std::size_t k) { return key(now[k]); }, [&](std::size_t k) { return has(old[k]); },
      [&](std::size_t from, std::size_t to) { copy(old[from], now[to]); });
}

}  // namespace slender
