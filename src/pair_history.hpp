// Per-pair history (friction springs, the side a contact was made from) carried from
// one pair list to the next. Pairs are matched by node ids, never by positions in the
// edge list: a chain that grows at its front (injection) renumbers every edge, and
// matching by edge number handed each contact's history to the neighbouring edge —
// across a hairpin the remembered side then looked crossed and the "push back"
// force blew the wire apart (2D crumpling, f = 50).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace slender {

// A key of two node ids (unordered when `symmetric`).
inline std::uint64_t node_pair_key(int a, int b, bool symmetric = false) {
  if (symmetric && b < a) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// For every entry of `now` whose key(entry) matches an entry of `old` that has
// history (has(entry)), copy(old entry, new entry). Only entries with history go
// into the lookup, so a rebuild costs little more than before.
template <class Entry, class Key, class Has, class Copy>
void carry_pair_history(const std::vector<Entry>& old, std::vector<Entry>& now, Key key, Has has,
                        Copy copy) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  for (std::size_t k = 0; k < old.size(); ++k)
    if (has(old[k])) index.emplace(key(old[k]), k);
  if (index.empty()) return;
  for (auto& e : now)
    if (auto it = index.find(key(e)); it != index.end()) copy(old[it->second], e);
}

}  // namespace slender
