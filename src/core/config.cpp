// SPDX-License-Identifier: MIT
// Parameter schema, validation and INI reading.
#include "emergent/config.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "emergent/error.hpp"

namespace emergent {

namespace {
std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

ParamSpec spec(const std::string& name, ParamType type, const std::string& def,
               const std::string& unit, const std::string& help) {
    ParamSpec p;
    p.name = name;
    p.type = type;
    p.default_value = def;
    p.unit = unit;
    p.help = help;
    return p;
}

// Shortest text that reads back as exactly v (defaults must not lose digits).
std::string number_text(double v) {
    for (int digits = 6; digits <= 17; ++digits) {
        std::ostringstream o;
        o.precision(digits);
        o << v;
        if (std::strtod(o.str().c_str(), nullptr) == v) return o.str();
    }
    return std::to_string(v);
}
}  // namespace

namespace {
/// A decimal number: [+-] digits [. digits] [e [+-] digits], with digits on at least one side
/// of the point. strtod alone also takes hexadecimal ("0x64"), "inf" and "nan", which would
/// reach output files as text.
bool is_decimal(const std::string& t) {
    std::size_t k = 0, digits = 0;
    auto run = [&] {
        std::size_t n = 0;
        while (k < t.size() && t[k] >= '0' && t[k] <= '9') ++k, ++n;
        return n;
    };
    if (k < t.size() && (t[k] == '+' || t[k] == '-')) ++k;
    digits += run();
    if (k < t.size() && t[k] == '.') ++k, digits += run();
    if (digits == 0) return false;
    if (k < t.size() && (t[k] == 'e' || t[k] == 'E')) {
        ++k;
        if (k < t.size() && (t[k] == '+' || t[k] == '-')) ++k;
        if (run() == 0) return false;
    }
    return k == t.size();
}
}  // namespace

double parse_number(const std::string& what, const std::string& text) {
    const char* s = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = is_decimal(text) ? std::strtod(s, &end) : 0.0;
    if (!is_decimal(text) || end != s + text.size() || errno == ERANGE || !std::isfinite(v))
        throw InputError(what + "='" + text + "' is not a number");
    return v;
}

bool parse_counts(const std::string& text, Int3& out) {
    char x1 = 0, x2 = 0, extra = 0;
    std::istringstream in(text);
    Int3 n{0, 0, 0};
    if (!(in >> n.x >> x1 >> n.y >> x2 >> n.z) || x1 != 'x' || x2 != 'x' || (in >> extra) ||
        n.x < 1 || n.y < 1 || n.z < 1)
        return false;
    out = n;
    return true;
}

std::pair<std::string, std::string> split_assignment(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || trim(text.substr(0, eq)).empty())
        throw InputError("'" + text + "' is not of the form key=value");
    return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
}

std::string ParamSpec::range_text() const {
    if (type == ParamType::Choice) {
        std::string s = "one of:";
        for (std::size_t k = 0; k < choices.size(); ++k) s += (k ? ", " : " ") + choices[k];
        return s;
    }
    if (type == ParamType::Text) return "";
    const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
    if (has_min && has_max)
        return (min_exclusive ? "> " + number_text(min) + " and <= " : number_text(min) + " .. ") +
               number_text(max);
    if (has_min) return (min_exclusive ? "> " : ">= ") + number_text(min);
    if (has_max) return "<= " + number_text(max);
    return "";
}

void ParamSpec::validate(const std::string& scene, const std::string& value) const {
    const std::string item = scene + ": " + name;
    if (type == ParamType::Text) return;
    if (type == ParamType::Choice) {
        for (const auto& c : choices)
            if (c == value) return;
        throw InputError(item + "=" + value + " must be " + range_text());
    }
    const double v = parse_number(item, value);
    if (type == ParamType::Integer && v != std::floor(v))
        throw InputError(item + "=" + value + " must be an integer");
    const bool below = min_exclusive ? !(v > min) : v < min;
    if (below || v > max) throw InputError(item + "=" + value + " must be " + range_text());
}

Schema& Schema::integer(const std::string& name, long long def, double min, double max,
                        const std::string& unit, const std::string& help) {
    ParamSpec p = spec(name, ParamType::Integer, std::to_string(def), unit, help);
    p.min = min;
    p.max = max;
    params_.push_back(p);
    return *this;
}

Schema& Schema::real(const std::string& name, double def, double min, double max,
                     const std::string& unit, const std::string& help, bool min_exclusive) {
    ParamSpec p = spec(name, ParamType::Real, number_text(def), unit, help);
    p.min = min;
    p.max = max;
    p.min_exclusive = min_exclusive;
    params_.push_back(p);
    return *this;
}

Schema& Schema::text(const std::string& name, const std::string& def, const std::string& help) {
    params_.push_back(spec(name, ParamType::Text, def, "", help));
    return *this;
}

Schema& Schema::choice(const std::string& name, const std::string& def,
                       const std::vector<std::string>& choices, const std::string& help) {
    ParamSpec p = spec(name, ParamType::Choice, def, "", help);
    p.choices = choices;
    params_.push_back(p);
    return *this;
}

Schema& Schema::set_default(const std::string& name, const std::string& def) {
    for (auto& p : params_)
        if (p.name == name) {
            p.default_value = def;
            return *this;
        }
    throw std::logic_error("set_default: no parameter " + name);
}

Schema& Schema::earlier_value(const std::string& name, const std::string& value) {
    for (auto& p : params_)
        if (p.name == name) {
            p.validate("earlier_value", value);
            p.earlier_value = value;
            return *this;
        }
    throw std::logic_error("earlier_value: no parameter " + name);
}

namespace {
void mark(std::vector<ParamSpec>& params, std::initializer_list<const char*> names, RestartRule rule) {
    for (const char* name : names) {
        bool found = false;
        for (auto& p : params)
            if (p.name == name) p.restart = rule, found = true;
        if (!found) throw std::logic_error(std::string("restart rule for unknown parameter ") + name);
    }
}
}  // namespace

Schema& Schema::structural(std::initializer_list<const char*> names) {
    mark(params_, names, RestartRule::Structural);
    return *this;
}

Schema& Schema::adjustable(std::initializer_list<const char*> names) {
    mark(params_, names, RestartRule::Adjustable);
    return *this;
}

const ParamSpec* Schema::find(const std::string& name) const {
    for (const auto& p : params_)
        if (p.name == name) return &p;
    return nullptr;
}

long long Config::integer(const std::string& name) const {
    return static_cast<long long>(std::llround(real(name)));
}

double Config::real(const std::string& name) const {
    return parse_number(scene_ + ": " + name, text(name));
}

const std::string& Config::text(const std::string& name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) throw std::logic_error("config: no parameter " + name);
    return it->second;
}

namespace {
/// The line without its comment: from a '#' or ';' that starts the line or follows white space.
std::string strip_comment(const std::string& line) {
    for (std::size_t k = 0; k < line.size(); ++k)
        if ((line[k] == '#' || line[k] == ';') && (k == 0 || line[k - 1] == ' ' || line[k - 1] == '\t'))
            return line.substr(0, k);
    return line;
}
}  // namespace

std::vector<Assignment> read_ini(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError("cannot read config file '" + path + "'");
    std::vector<Assignment> entries;
    std::map<std::string, int> first_line;
    std::string line, section;
    for (int number = 1; std::getline(in, line); ++number) {
        line = trim(strip_comment(line));
        if (line.empty()) continue;
        const std::string where = path + ":" + std::to_string(number);
        // A control byte (a NUL would cut the message short) means this is no INI text.
        for (const char c : line)
            if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
                throw InputError(where + ": not a line of text (control bytes): is '" + path +
                                 "' an INI file?");
        if (line.front() == '[') {
            if (line.back() != ']' || line.size() < 3)
                throw InputError(where + ": malformed section header '" + line + "'");
            section = trim(line.substr(1, line.size() - 2)) + ".";
            continue;
        }
        const auto eq = line.find('=');
        if (eq == std::string::npos || trim(line.substr(0, eq)).empty())
            throw InputError(where + ": expected 'key = value', got '" + line + "'");
        const std::string key = section + trim(line.substr(0, eq));
        const auto [it, fresh] = first_line.emplace(key, number);
        if (!fresh)
            throw InputError(where + ": '" + key + "' is set twice (first at line " +
                             std::to_string(it->second) + ")");
        entries.push_back({key, trim(line.substr(eq + 1)), " at " + where});
    }
    if (in.bad()) throw InputError("cannot read config file '" + path + "'");
    return entries;
}

}  // namespace emergent
