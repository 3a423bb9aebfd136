#pragma once
/// A graph written back to the file it came from, so that the file stays readable and a diff
/// shows only the edit: the file's own key order (what is new goes after it), values the
/// edit left alone spelled as the file spelled them (100 stays 100, not 100.0), parameters
/// the file set kept even where they now equal their defaults; two-space indent, arrays of
/// numbers and strings on one line.

#include <string>

#include "core/Graph.h"

namespace cg {

/// `graph` as file text, laid out like `layout` (the file's text as last loaded or saved;
/// empty or not a JSON object: the order header, nodes; type, inputs, params, comment).
std::string graphFileText(const Graph& graph, const std::string& layout);

}  // namespace cg
