// `cloudgraph nodes`: every registered node type gets a one-line summary that is its doc's
// whole first sentence, never blank and never cut inside an abbreviation like "Sec." or "e.g.".

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <sstream>
#include <string>

#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

/// type -> summary, from the lines of `cloudgraph nodes` ("TYPE  summary").
std::map<std::string, std::string> summaries(const std::string& output)
{
    std::map<std::string, std::string> out;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        const auto space = line.find(' ');
        const auto text = line.find_first_not_of(' ', space);
        out[line.substr(0, space)] = text == std::string::npos ? "" : line.substr(text);
    }
    return out;
}

/// The word before the final '.', lower-cased: "Sec." -> "sec", "(e.g." -> "e.g".
std::string lastWord(const std::string& s)
{
    std::size_t begin = s.size() - 1;
    while (begin > 0 &&
           (std::isalpha(static_cast<unsigned char>(s[begin - 1])) || s[begin - 1] == '.'))
        --begin;
    std::string word = s.substr(begin, s.size() - 1 - begin);
    for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return word;
}

}  // namespace

TEST(NodesSummary, EveryBuiltinNodeHasAWholeFirstSentence)
{
    Registry registry;
    registerBuiltinNodes(registry);
    const auto r = test::runCli({"nodes"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    const auto found = summaries(r.output);
    ASSERT_GE(registry.nodes().size(), 30u);
    for (const NodeDecl* d : registry.nodes()) {
        SCOPED_TRACE(d->type);
        ASSERT_EQ(found.count(d->type), 1u) << r.output;
        const std::string& s = found.at(d->type);
        if (s.empty()) {
            ADD_FAILURE() << "blank summary";
            continue;
        }
        EXPECT_NE(std::string(".!?").find(s.back()), std::string::npos) << s;
        // The doc's own words, up to a sentence end: nothing cut in the middle of a word.
        EXPECT_TRUE(d->doc.compare(0, s.size(), s) == 0) << s;
        EXPECT_TRUE(s.size() == d->doc.size() ||
                    std::isspace(static_cast<unsigned char>(d->doc[s.size()])))
            << s;
        for (const char* abbreviation :
             {"sec", "eq", "eqs", "fig", "e.g", "i.e", "approx", "cf", "al"})
            EXPECT_NE(lastWord(s), abbreviation) << s;
        EXPECT_FALSE(s.size() >= 3 && s.compare(s.size() - 3, 3, "...") == 0) << s;
        int open = 0;  // a cut inside "(Sec. 4, ...)" leaves a parenthesis open
        for (const char c : s) open = c == '(' ? open + 1 : c == ')' ? std::max(0, open - 1) : open;
        EXPECT_EQ(open, 0) << s;
    }
}

TEST(NodesSummary, OneSentenceDocsAndAbbreviationsReadWhole)
{
    const auto found = summaries(test::runCli({"nodes"}).output);
    // Docs of one sentence (the old logic printed nothing for them).
    EXPECT_EQ(found.at("Constant"), "A number, set by its parameter.");
    // "Sec. 5.1" and "(e.g. the Renderer's)" do not end the sentence.
    EXPECT_EQ(
        found.at("NoiseMap").rfind("The 2D 1/f^beta density map fNoise(ix, iy) of Sec. 5.1 (", 0),
        0u);
    EXPECT_EQ(found.at("WriteImage"), "Writes an image of linear radiance (e.g. the Renderer's).");
    EXPECT_EQ(found.at("PrimitiveMapper"),
              "The recursive mapping of Sec. 5.2 (pseudocode lines 15-28).");
}

}  // namespace cg
