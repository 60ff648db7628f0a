#include <gtest/gtest.h>

#include "core/base/error.hpp"
#include "core/base/options/param_value.hpp"
#include "core/base/options/params.hpp"
#include "core/base/options/render_options.hpp"

using namespace weft;

namespace {

ParamTable table() {
    return ParamTable("demo", {floatParam("step", 0.5, 1e-4, 64, "step"), intParam("count", 4, 1, 16, "count"),
                               boolParam("jitter", false, "jitter"), enumParam("mode", "a", {"a", "b"}, "mode")});
}

std::string errorOf(const std::map<std::string, std::string>& given) {
    try {
        table().parse(given);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Params, DefaultsFillEveryParameterInTableOrder) {
    const ParamSet set = table().parse({});
    EXPECT_DOUBLE_EQ(set.getFloat("step"), 0.5);
    EXPECT_EQ(set.getInt("count"), 4);
    EXPECT_FALSE(set.getBool("jitter"));
    EXPECT_EQ(set.getString("mode"), "a");
    ASSERT_EQ(set.values().size(), 4u);
    EXPECT_EQ(set.values()[0].first, "step");
    EXPECT_FALSE(set.wasSet("step"));
}

TEST(Params, GivenValuesAreConvertedAndCanonical) {
    const ParamSet set = table().parse({{"step", "0.250"}, {"jitter", "on"}, {"count", "8"}});
    EXPECT_DOUBLE_EQ(set.getFloat("step"), 0.25);
    EXPECT_EQ(set.values()[0].second, "0.25");
    EXPECT_TRUE(set.getBool("jitter"));
    EXPECT_TRUE(set.wasSet("step"));
}

TEST(Params, OutOfRangeNamesKeyValueAndRange) {
    const std::string msg = errorOf({{"step", "100"}});
    EXPECT_NE(msg.find("'step'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'100'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[1e-04, 64]"), std::string::npos) << msg;
}

TEST(Params, UnknownKeyListsValidOnes) {
    const std::string msg = errorOf({{"stepp", "1"}});
    EXPECT_NE(msg.find("unknown parameter 'stepp'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("step, count, jitter, mode"), std::string::npos) << msg;
}

TEST(Params, RejectsNonNumbersNonIntegersAndBadEnums) {
    EXPECT_NE(errorOf({{"step", "abc"}}).find("not a number"), std::string::npos);
    EXPECT_NE(errorOf({{"step", "nan"}}).find("not a number"), std::string::npos);
    EXPECT_NE(errorOf({{"step", "inf"}}).find("not a number"), std::string::npos);
    EXPECT_NE(errorOf({{"count", "2.5"}}).find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf({{"mode", "c"}}).find("one of a|b"), std::string::npos);
    EXPECT_NE(errorOf({{"jitter", "maybe"}}).find("true|false"), std::string::npos);
}

// One rule for --set parameters and the render options (--spp, --seed...):
// a text one takes, the other takes, with the same canonical value.
TEST(Params, TechniqueParametersAndRenderOptionsCheckNumbersAlike) {
    const RenderOption* spp = findRenderOption("spp", kOnCommandLine);
    ASSERT_NE(spp, nullptr);
    const ParamTable sppTable("demo", {spp->spec});
    for (const std::string text : {"16", "1e2", "16.0", "+5", "0x10", " 5", "5 ", "inf", "nan", "2.5", "0", "-3", "1e300", ""}) {
        const ParamValue v = checkParamValue(spp->spec, text);
        RenderRequest r;
        bool optionTakes = true, paramTakes = true;
        try {
            applyRenderOption(r, *spp, text, "--spp");
        } catch (const Error&) {
            optionTakes = false;
        }
        try {
            sppTable.parse({{"spp", text}});
        } catch (const Error&) {
            paramTakes = false;
        }
        EXPECT_EQ(optionTakes, v.fault == ParamValue::Fault::None) << "'" << text << "'";
        EXPECT_EQ(paramTakes, optionTakes) << "'" << text << "'";
        if (optionTakes) EXPECT_EQ(std::to_string(*r.spp), v.canonical) << "'" << text << "'";
    }
    EXPECT_EQ(checkParamValue(spp->spec, "16").canonical, "16");
    EXPECT_EQ(checkParamValue(spp->spec, "1e2").canonical, "100");
    EXPECT_EQ(checkParamValue(spp->spec, "+5").fault, ParamValue::Fault::NotNumber);
    EXPECT_EQ(checkParamValue(spp->spec, "2.5").fault, ParamValue::Fault::NotInteger);
    EXPECT_EQ(checkParamValue(spp->spec, "0").fault, ParamValue::Fault::OutOfRange);
}

TEST(Params, HelpTextListsEveryParameterWithRange) {
    const std::string help = table().helpText();
    for (const char* s : {"step", "count", "jitter", "mode", "[1, 16]", "one of a|b"})
        EXPECT_NE(help.find(s), std::string::npos) << s;
}

TEST(Params, MarkdownTableHasOneRowPerParameterAndEscapesBars) {
    const ParamTable t("demo", {floatParam("step", 0.5, 1e-4, 64, "step in voxels"), boolParam("jitter", false, "a|b"),
                                enumParam("mode", "a", {"a", "b"}, "mode"), stringParam("pattern", "", "spec")});
    EXPECT_EQ(t.markdownTable(),
              "| parameter | type | default | allowed | meaning |\n"
              "|---|---|---|---|---|\n"
              "| `step` | float | `0.5` | [1e-04, 64] | step in voxels |\n"
              "| `jitter` | bool | `false` | `true`, `false` | a\\|b |\n"
              "| `mode` | enum | `a` | `a`, `b` | mode |\n"
              "| `pattern` | string | (empty) | text | spec |\n");
    EXPECT_EQ(ParamTable("none", {}).markdownTable(), "No parameters.\n");
}

TEST(ErrorText, PrintableLineEscapesRawBytesAndKeepsUtf8) {
    EXPECT_EQ(weft::printableLine("plain text"), "plain text");
    EXPECT_EQ(weft::printableLine("two\nlines\tand tab"), "two lines and tab");
    EXPECT_EQ(weft::printableLine(std::string("bytes \x01\x9f\xff end", 13)), "bytes \\x01\\x9F\\xFF end");
    EXPECT_EQ(weft::printableLine("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");  // valid UTF-8 stays
    EXPECT_EQ(weft::printableLine("cut \xe2\x82"), "cut \\xE2\\x82");                      // a cut sequence does not
    // Lead bytes no UTF-8 has, overlong forms, surrogates and code points past U+10FFFF are escaped.
    EXPECT_EQ(weft::printableLine("\xf5\x80\x80"), "\\xF5\\x80\\x80");
    EXPECT_EQ(weft::printableLine("\xff\xbf\xbf"), "\\xFF\\xBF\\xBF");
    EXPECT_EQ(weft::printableLine("\xe0\x80\xaf"), "\\xE0\\x80\\xAF");
    EXPECT_EQ(weft::printableLine("\xed\xa0\x80"), "\\xED\\xA0\\x80");
    EXPECT_EQ(weft::printableLine("\xf4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");
    EXPECT_EQ(weft::printableLine("\xf0\x9f\x98\x80"), "\xf0\x9f\x98\x80");  // U+1F600 stays
}
