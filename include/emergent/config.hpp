// SPDX-License-Identifier: MIT
// Parameter schemas (name, type, default, unit, range) and the resolved configuration of a run.
#pragma once

#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

enum class ParamType { Integer, Real, Text, Choice };

/// Whether a parameter may change when a run continues from a checkpoint.
/// Structural: it shapes what the checkpoint holds (geometry, particle count, species, field
/// grids, the scene's structure); a continued run refuses a new value. Adjustable: dt, skin,
/// integrator, thermostat, interaction strengths, driving, run control: a continued run takes
/// the new value and says so. Unmarked parameters (e.g. an older plugin's) count as structural.
enum class RestartRule { Unmarked, Structural, Adjustable };

/// One parameter a scene (or the engine) accepts.
struct ParamSpec {
    std::string name;
    ParamType type = ParamType::Real;
    std::string default_value;
    std::string unit;  ///< reduced MD units: "sigma", "tau", "epsilon", "1" for dimensionless
    std::string help;
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_exclusive = false;  ///< true: value must be > min rather than >= min
    std::vector<std::string> choices;
    RestartRule restart = RestartRule::Unmarked;
    /// The value runs had built in before this parameter existed ("": its default): what a
    /// checkpoint written then continues with, where a later default differs.
    std::string earlier_value;

    /// Throws InputError naming `scene` and this parameter if `value` is not acceptable.
    void validate(const std::string& scene, const std::string& value) const;
    /// "> 0", "1 .. 100", "one of: none, bussi", "" when unrestricted.
    std::string range_text() const;
};

/// Ordered list of parameters; the order is the one `emergent help` prints.
class Schema {
public:
    Schema& integer(const std::string& name, long long def, double min, double max,
                    const std::string& unit, const std::string& help);
    Schema& real(const std::string& name, double def, double min, double max,
                 const std::string& unit, const std::string& help, bool min_exclusive = false);
    Schema& text(const std::string& name, const std::string& def, const std::string& help);
    Schema& choice(const std::string& name, const std::string& def,
                   const std::vector<std::string>& choices, const std::string& help);
    /// Changes the default of an existing parameter (a scene adapting an engine parameter).
    Schema& set_default(const std::string& name, const std::string& def);
    /// Marks parameters (already added) for continued runs: see RestartRule.
    Schema& structural(std::initializer_list<const char*> names);
    Schema& adjustable(std::initializer_list<const char*> names);
    /// Records the value `name` had in effect before it became a parameter (see
    /// ParamSpec::earlier_value), for a default that changes after checkpoints without it exist.
    Schema& earlier_value(const std::string& name, const std::string& value);

    const ParamSpec* find(const std::string& name) const;
    const std::vector<ParamSpec>& params() const { return params_; }

private:
    std::vector<ParamSpec> params_;
};

/// Fully resolved parameters of one run: every schema entry has a validated value.
class Config {
public:
    Config() = default;
    Config(std::string scene, std::map<std::string, std::string> values)
        : scene_(std::move(scene)), values_(std::move(values)) {}

    const std::string& scene() const { return scene_; }
    long long integer(const std::string& name) const;
    double real(const std::string& name) const;
    const std::string& text(const std::string& name) const;
    const std::map<std::string, std::string>& values() const { return values_; }

private:
    std::string scene_;
    std::map<std::string, std::string> values_;
};

/// One `key = value` of a configuration source, with where it came from (for error messages:
/// " at FILE:LINE" for INI files, "" for the command line).
struct Assignment {
    std::string key, value, origin;
};

/// Reads `key = value` lines of an INI file, in file order. `[section]` prefixes the keys after
/// it as `section.key`. A comment starts at '#' or ';' at the start of a line or after white
/// space; a '#' or ';' inside a word belongs to the value (`name = a#b` is "a#b";
/// `name = a #b` is "a"). Throws InputError naming the file and line for a malformed line and
/// for a key given twice in one file.
std::vector<Assignment> read_ini(const std::string& path);

/// Splits "key=value"; throws InputError for anything else.
std::pair<std::string, std::string> split_assignment(const std::string& text);

/// Parses "AxBxC" (three positive integers, e.g. a rank grid or cell counts) into `out`;
/// false for anything else, so the caller can name the item in its error.
bool parse_counts(const std::string& text, Int3& out);

/// Parses a finite number, or throws InputError naming `what`.
double parse_number(const std::string& what, const std::string& text);

}  // namespace emergent
