#pragma once
/// The error a file reader throws for a file it cannot read as its format. The formats library
/// knows nothing of graphs or nodes; a std::invalid_argument, it leaves a node's cook as bad
/// input (exit 2) naming the node and the file (core/Evaluator.cc), without a catch in the node.

#include <stdexcept>
#include <string>

namespace cg::formats {

class FormatError : public std::invalid_argument {
public:
    /// `where`: the file, or "<file>:<byte offset>" when the fault is at a known place.
    FormatError(std::string where, const std::string& message)
        : std::invalid_argument(where + ": " + message), mWhere(std::move(where)), mMessage(message)
    {
    }
    const std::string& where() const { return mWhere; }
    const std::string& message() const { return mMessage; }

private:
    std::string mWhere;
    std::string mMessage;
};

}  // namespace cg::formats
