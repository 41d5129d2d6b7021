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
