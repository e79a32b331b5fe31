// Every switch of a mode, declared once. The command line's options, their
// help, the validation of a value, the "switches" object of a result, a
// baseline's re-run by `check` and compare's MODE+SWITCH=VALUE all come from
// this table: adding a switch is one entry here plus its implementation.
//
// A switch has a name ("share_quantum": the key in results and scene files;
// the command line spells it --share-quantum) and a value as users type it
// ("on", "per-copy", "1/30"). lib/ reports a bad value in its own terms, by the
// switch's name; cli/ puts the option's spelling in front.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "base/modes.h"

namespace crowdprof {

struct SwitchSpec {
  std::string_view name;   // result and scene key; the option is --name with '-' for '_'
  std::string_view value;  // how a value looks, for help: "on|off", "SECONDS", "A,B,C"
  std::string_view help;
  // The switch's value in `s` as a result records it: a string, true/false, or
  // a number.
  nlohmann::json (*get)(const ModeSwitches& s);
  // Sets the switch in `s` from a value as users type it. Returns "" or what is
  // wrong with the value ("expected on or off").
  std::string (*set)(ModeSwitches& s, std::string_view text);
  // Recorded in a result even at its default value. The switches added after
  // the thesis's are recorded only when set, so results made before them still
  // match the same mode.
  bool always_recorded = true;
  // The value a result that lacks the switch ran with, when it is not today's
  // default (a default changed after results were recorded); such a switch is
  // always recorded. Empty: the default.
  std::string_view when_absent = {};
  // The option may be given several times (--anim-layer): the values join
  // one a line, which `set` takes as it takes ';'.
  bool repeatable = false;
};

// In the order help lists them.
std::span<const SwitchSpec> switch_table();
const SwitchSpec* find_switch(std::string_view name);

// "lookups, culling, pose, ...".
std::string switch_names();

// "--share-quantum" for "share_quantum".
std::string option_spelling(std::string_view name);

// A recorded value back as users type it: strings as they are, booleans as
// on/off, numbers in the shortest form that reads back the same.
std::string switch_text(const nlohmann::json& value);

// A recorded value for a reader: as switch_text, but a fraction to 3
// significant digits (1/30 s as "0.0333", not "0.03333333333333333").
std::string readable_switch_text(const nlohmann::json& value);

// The switches whose values differ between `a` and `b`, in the table's order
// and as a reader reads them: {"--culling on, --share-quantum 0.0333",
// "--culling off, --share-quantum 0"}; both empty when none differs.
std::pair<std::string, std::string> switch_differences(const ModeSwitches& a, const ModeSwitches& b);

// The value of switch `spec` in `s` as users type it.
std::string switch_text(const SwitchSpec& spec, const ModeSwitches& s);

// A result's "switches" object for `s`.
nlohmann::json switches_to_json(const ModeSwitches& s);

// Reads a result's "switches" object: a switch it leaves out holds its default
// (results made before the switch existed ran with that value), or its
// when_absent value. Returns "" or
// what is wrong ("culling: expected on or off", "no switch 'x'").
std::string switches_from_json(const nlohmann::json& switches, ModeSwitches& s);

// Each preset's value of the switch, for help, grouped by value: "off in
// master; on in the others".
std::string preset_values(const SwitchSpec& spec);

}  // namespace crowdprof
