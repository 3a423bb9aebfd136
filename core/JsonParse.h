#pragma once
/// Strict JSON reading for graph files, and helpers for pointing at a place in them.

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace cg {

/// Parses `text` as one JSON document, refusing what nlohmann would accept silently.
/// Throws InputError for:
///  - empty or whitespace-only text ("file is empty", where = sourceName);
///  - syntax errors (where = "sourceName:line L, column C (byte B)", B 1-based like nlohmann);
///  - numbers that overflow a double (where = sourceName:pointer, "not finite");
///  - nesting deeper than maxDepth containers (the top-level value is depth 1), refused as
///    soon as it is exceeded (where = sourceName:pointer of the offending container);
///  - a key repeated in one object (where = sourceName:pointer of the key, "duplicate key").
/// nlohmann's SAX parser is iterative, so deep input cannot overflow the stack.
nlohmann::json parseJsonStrict(const std::string& text, const std::string& sourceName,
                               int maxDepth);

/// One reference token of a JSON pointer, escaped ("~" -> "~0", "/" -> "~1").
std::string jsonPointerToken(const std::string& key);

/// `text` with control characters other than newline and tab written as \xNN, for quoting
/// user input in a message (a node id with a NUL in it would cut the printed message short).
std::string printableText(const std::string& text);

/// The candidate closest to `word` by edit distance, if within 2 edits; otherwise empty.
std::string closestName(const std::string& word, const std::vector<std::string>& candidates);

/// "; did you mean 'x'?" for the closest candidate, or empty.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace cg
