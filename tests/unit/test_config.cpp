// SPDX-License-Identifier: MIT
// Parameter schemas, presets, INI files and overrides.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "emergent/error.hpp"
#include "emergent/problem.hpp"

using namespace emergent;

namespace {
const ProblemInfo& lj() { return *ProblemRegistry::instance().find("lj-fluid"); }

std::string temp_file(const std::string& content) {
    char name[] = "/tmp/emergent_config_XXXXXX";
    const int fd = mkstemp(name);
    if (fd >= 0) close(fd);
    std::ofstream(name) << content;
    return name;
}
}  // namespace

TEST(Config, DefaultsPresetsFilesAndSetsOverrideInOrder) {
    // A [section] prefixes the keys after it: "run.n_cells" is not an lj-fluid parameter.
    const std::string ini = temp_file("# comment\n[run]\nn_cells = 7\n");
    EXPECT_THROW(resolve_config(lj(), "", {ini}, {}), InputError);
    const std::string ok = temp_file("n_cells = 7 ; trailing comment\ndensity=0.7\n");
    const Config c = resolve_config(lj(), "tiny", {ok}, {"density=0.6"});
    EXPECT_EQ(c.integer("n_cells"), 7);           // file beats preset
    EXPECT_DOUBLE_EQ(c.real("density"), 0.6);     // --set beats file
    EXPECT_EQ(c.integer("steps"), 200);           // from preset
    EXPECT_DOUBLE_EQ(c.real("cutoff"), 1.122462048309373);  // default kept to full precision
    std::remove(ini.c_str());
    std::remove(ok.c_str());
}

TEST(Config, BadValuesNameTheItem) {
    auto message = [](const std::vector<std::string>& sets) {
        try {
            resolve_config(lj(), "", {}, sets);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({"bogus=1"}).find("unknown parameter 'bogus'"), std::string::npos);
    EXPECT_NE(message({"density=-1"}).find("density=-1 must be > 0"), std::string::npos);
    EXPECT_NE(message({"n_cells=2.5"}).find("must be an integer"), std::string::npos);
    EXPECT_NE(message({"dt=abc"}).find("dt='abc' is not a number"), std::string::npos);
    EXPECT_NE(message({"thermostat=nose"}).find("one of: none, bussi"), std::string::npos);
    EXPECT_NE(message({"novalue"}).find("not of the form key=value"), std::string::npos);
    EXPECT_THROW(resolve_config(lj(), "huge", {}, {}), InputError);
}

TEST(Config, MalformedIniNamesFileAndLine) {
    const std::string bad = temp_file("n_cells = 4\nthis line has no equals sign\n");
    try {
        read_ini(bad);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(bad + ":2"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_ini("/nonexistent/file.ini"), InputError);
    std::remove(bad.c_str());
}

// A key given twice in one file is an error at the second line, naming the first.
TEST(Config, DuplicateIniKeyNamesBothLines) {
    const std::string twice = temp_file("density = 0.7\n# note\n[x]\nn = 1\n[]\n");
    const std::string dup = temp_file("density = 0.7\nn_cells = 5\ndensity = 0.6\n");
    try {
        read_ini(dup);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(dup + ":3: 'density' is set twice (first at line 1)"),
                  std::string::npos) << e.what();
    }
    // The same key in two sections is two keys.
    const std::string sections = temp_file("[a]\nk = 1\n[b]\nk = 2\n");
    EXPECT_EQ(read_ini(sections).size(), 2u);
    std::remove(twice.c_str());
    std::remove(dup.c_str());
    std::remove(sections.c_str());
}

// Unknown keys and bad values from a file name the file and line.
TEST(Config, FileErrorsKeepTheLine) {
    const std::string unknown = temp_file("n_cells = 4\n\nbogus = 1\n");
    const std::string bad = temp_file("density = -2\n");
    auto message = [](const std::string& file) {
        try {
            resolve_config(lj(), "", {file}, {});
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(unknown).find("unknown parameter 'bogus' at " + unknown + ":3"), std::string::npos)
        << message(unknown);
    EXPECT_NE(message(bad).find("density=-2 must be > 0 and <= 1.5 at " + bad + ":1"), std::string::npos)
        << message(bad);
    std::remove(unknown.c_str());
    std::remove(bad.c_str());
}

// '#' and ';' start a comment at the start of a line or after white space; inside a word they
// belong to the value.
TEST(Config, CommentsStartAfterWhiteSpaceOnly) {
    const std::string f = temp_file("; first\n  # indented\na = x#y\nb = x #y\nc = x;y\nd = x\t;y\ne = #all\n");
    const auto entries = read_ini(f);
    ASSERT_EQ(entries.size(), 5u);
    EXPECT_EQ(entries[0].value, "x#y");
    EXPECT_EQ(entries[1].value, "x");
    EXPECT_EQ(entries[2].value, "x;y");
    EXPECT_EQ(entries[3].value, "x");
    EXPECT_EQ(entries[4].value, "");
    EXPECT_EQ(entries[2].origin, " at " + f + ":5");
    std::remove(f.c_str());
}

// Numbers are decimal only: hexadecimal, inf and nan would reach output files as text.
TEST(Config, NumbersAreDecimal) {
    for (const char* ok : {"100", "+1.5", "-.5", "5.", "1e5", "2.5E-3"})
        EXPECT_NO_THROW(parse_number("x", ok)) << ok;
    for (const char* bad : {"0x64", "inf", "nan", "1e", ".", "1.2.3", " 1", "1 ", "", "e5", "--1"})
        EXPECT_THROW(parse_number("x", bad), InputError) << bad;
    EXPECT_THROW(resolve_config(lj(), "", {}, {"steps=0x64"}), InputError);
}

// Every parameter of every scene says whether a continued run may change it.
TEST(Config, EveryParameterHasARestartRule) {
    for (const ProblemInfo* info : ProblemRegistry::instance().all())
        for (const ParamSpec& p : info->schema.params())
            EXPECT_NE(p.restart, RestartRule::Unmarked) << info->name << ": " << p.name;
}
