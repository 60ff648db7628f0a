// The technique pages: every registered technique has docs/techniques/NAME.md,
// and the part of it between "<!-- BEGIN weft help NAME --markdown -->" and
// "<!-- END weft help NAME --markdown -->" is exactly what the binary prints
// for `weft help NAME --markdown` now (scripts/gen-docs.sh rewrites it).
// The README's technique table links every page; docs/usage.md holds
// `weft help options --markdown` between its markers.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "tests/support/test_support.hpp"

using namespace weft::test;
namespace fs = std::filesystem;

namespace {

// External plugins on the caller's WEFT_PLUGIN_PATH have no pages here.
const char* kNoPlugins = "env -u WEFT_PLUGIN_PATH";

const fs::path kPages = fs::path(WEFT_SOURCE_DIR) / "docs" / "techniques";

std::set<std::string> registeredTechniques() {
    const CommandResult r = runWeft("--list-plugins", kNoPlugins);
    EXPECT_EQ(r.status, 0) << r.output;
    std::set<std::string> names;
    std::istringstream lines(r.output);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::string name;
        if (words >> name) names.insert(name);
    }
    return names;
}

std::string beginMarker(const std::string& name) { return "<!-- BEGIN weft help " + name + " --markdown -->\n"; }
std::string endMarker(const std::string& name) { return "<!-- END weft help " + name + " --markdown -->\n"; }

// The text between the marker lines, or why there is none.
bool generatedPart(const std::string& page, const std::string& name, std::string& part) {
    const std::string begin = beginMarker(name), end = endMarker(name);
    const std::size_t b = page.find(begin);
    if (b == std::string::npos || (b > 0 && page[b - 1] != '\n')) return part = "no line " + begin, false;
    if (page.find(begin, b + 1) != std::string::npos) return part = "two lines " + begin, false;
    const std::size_t from = b + begin.size(), e = page.find(end, from);
    if (e == std::string::npos || page[e - 1] != '\n') return part = "no line " + end + " after " + begin, false;
    part = page.substr(from, e - from);
    return true;
}

}  // namespace

TEST(Docs, EveryRegisteredTechniqueHasAPage) {
    const std::set<std::string> names = registeredTechniques();
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names)
        EXPECT_TRUE(fs::is_regular_file(kPages / (name + ".md")))
            << "no page docs/techniques/" << name << ".md (scripts/gen-docs.sh starts one)";
}

TEST(Docs, EveryPageIsARegisteredTechnique) {
    const std::set<std::string> names = registeredTechniques();
    for (const auto& entry : fs::directory_iterator(kPages)) {
        if (entry.path().extension() != ".md") continue;
        EXPECT_TRUE(names.count(entry.path().stem().string())) << entry.path() << " documents no registered technique";
    }
}

TEST(Docs, GeneratedPartOfEveryPageIsWhatWeftHelpPrints) {
    for (const std::string& name : registeredTechniques()) {
        const fs::path page = kPages / (name + ".md");
        if (!fs::is_regular_file(page)) continue;  // EveryRegisteredTechniqueHasAPage says so
        const CommandResult help = runWeft("help " + name + " --markdown", kNoPlugins);
        ASSERT_EQ(help.status, 0) << help.output;
        std::string part;
        ASSERT_TRUE(generatedPart(readBytes(page), name, part)) << page.string() << ": " << part;
        EXPECT_EQ(part, help.output) << page.string()
                                     << " is out of date with `weft help " << name
                                     << " --markdown`: run scripts/gen-docs.sh";
    }
}

TEST(Docs, ReadmeLinksEveryTechniquePage) {
    const std::string readme = readBytes(fs::path(WEFT_SOURCE_DIR) / "README.md");
    for (const std::string& name : registeredTechniques())
        EXPECT_NE(readme.find("(docs/techniques/" + name + ".md)"), std::string::npos)
            << "README.md does not link docs/techniques/" << name << ".md";
}

TEST(Docs, HelpMarkdownNeedsATechniqueName) {
    const CommandResult r = runWeft("help --markdown");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("needs a technique name"), std::string::npos) << r.output;
}

// docs/usage.md holds the render option table and the counter list the same way.
TEST(Docs, UsageHoldsWhatWeftHelpRenderPrints) {
    const fs::path page = fs::path(WEFT_SOURCE_DIR) / "docs" / "usage.md";
    for (const std::string name : {"options", "counters"}) {
        const CommandResult help = runWeft("help " + name + " --markdown", kNoPlugins);
        ASSERT_EQ(help.status, 0) << help.output;
        std::string part;
        ASSERT_TRUE(generatedPart(readBytes(page), name, part)) << page.string() << ": " << part;
        EXPECT_EQ(part, help.output) << "docs/usage.md is out of date with `weft help " << name << " --markdown`: run scripts/gen-docs.sh";
    }
}
