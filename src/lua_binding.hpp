// The Lua 5.4 deck interface: module `slender`, Simulation userdata and the
// deck runner used by the `slender` program.
#pragma once

#include <map>
#include <string>
#include <vector>

struct lua_State;

namespace slender {

struct DeckOptions {
  std::string path;
  std::map<std::string, std::string> vars;  // -v name=value overrides
  bool quiet = false;
  std::string inventory;  // --inventory FILE: one JSON line per simulation when it is freed
  int threads = 0;        // -t N (0: OMP_NUM_THREADS, else 1) for every simulation of the deck
  // SIGINT / SIGTERM stop the runs cleanly (a last frame and checkpoint, exit code 130);
  // an embedding program that handles signals itself turns this off.
  bool catch_signals = true;
};

// Registers the `slender` module (global and for require) in a Lua state.
void open_slender(lua_State* L, const DeckOptions& opt);
// Closes a state opened with open_slender (its simulations are collected, their outputs
// flushed) and frees the module's context.
void close_slender(lua_State* L);

// Runs a deck; prints one error line on failure. Exit codes: 0 ok, 1 deck or
// input error, 3 instability, 130 stopped by SIGINT or SIGTERM (state written).
int run_deck(const DeckOptions& opt);
// Every deck call ("slender.simulation", "sim:run", ...), for the docs/decks.md check.
std::vector<std::string> deck_calls();

}  // namespace slender
