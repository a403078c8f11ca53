// scripts/demo and scripts/reference as a user calls them: --help and bad arguments are
// answered at once, before the build they would otherwise start (minutes), with one line
// naming the option and exit status 2.
#include <string>

#include <gtest/gtest.h>

#include "support/shell.h"

namespace {

using tessera::test::CliResult;
using tessera::test::run_shell;

CliResult script(const std::string& name, const std::string& args) {
    return run_shell("cd /tmp && " + std::string(TESSERA_SOURCE_DIR) + "/scripts/" + name + " " + args);
}

TEST(Scripts, HelpPrintsTheUsageWithoutBuilding) {
    for (const char* name : {"demo", "reference"}) {
        const CliResult r = script(name, "--help");
        EXPECT_EQ(r.exit_code, 0) << name << ": " << r.output;
        EXPECT_EQ(r.output.rfind(std::string("Usage: scripts/") + name, 0), 0u) << r.output;
        EXPECT_EQ(r.output.find("ninja"), std::string::npos) << "built:\n" << r.output;
    }
}

TEST(Scripts, ReferenceRefusesBadArgumentsBeforeBuilding) {
    const struct {
        const char* args;
        const char* message;
    } cases[] = {
        {"--spp", "reference: --spp needs a value (see scripts/reference --help)"},
        {"--spp=", "reference: --spp needs a value"},
        {"--method igi", "reference: unknown option --method"},
        {"no-such-scene.json", "reference: no-such-scene.json: no such scene file"},
    };
    for (const auto& c : cases) {
        const CliResult r = script("reference", c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.output;
        EXPECT_EQ(r.output.rfind(c.message, 0), 0u) << c.args << ": " << r.output;
        EXPECT_EQ(r.output.find("ninja"), std::string::npos) << "built:\n" << r.output;
    }
}

}  // namespace
