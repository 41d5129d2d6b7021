// SPDX-License-Identifier: MIT
// Parameter schemas (name, type, default, unit, range) and the resolved configuration of a run.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "emergent/vec3.hpp"

namespace emergent {

enum class ParamType { Integer, Real, Text, Choice };

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

/// Reads `key = value` lines of an INI file; `[section]` prefixes keys as `section.key`;
/// '#' and ';' start comments. Throws InputError with file and line on any malformed line.
std::map<std::string, std::string> read_ini(const std::string& path);

/// Splits "key=value"; throws InputError for anything else.
std::pair<std::string, std::string> split_assignment(const std::string& text);

/// Parses "AxBxC" (three positive integers, e.g. a rank grid or cell counts) into `out`;
/// false for anything else, so the caller can name the item in its error.
bool parse_counts(const std::string& text, Int3& out);

/// Parses a finite number, or throws InputError naming `what`.
double parse_number(const std::string& what, const std::string& text);

}  // namespace emergent
