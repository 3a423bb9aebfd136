#pragma once
/// The error a file reader throws for a file it cannot read as its format. The formats library
/// knows nothing of graphs or nodes: the node that reads the file turns this into the engine's
/// InputError (exit 2) with its node, parameter and JSON pointer.

#include <stdexcept>
#include <string>

namespace cg::formats {

class FormatError : public std::runtime_error {
public:
    /// `where`: the file, or "<file>:<byte offset>" when the fault is at a known place.
    FormatError(std::string where, const std::string& message)
        : std::runtime_error(where + ": " + message), mWhere(std::move(where)), mMessage(message)
    {
    }
    const std::string& where() const { return mWhere; }
    const std::string& message() const { return mMessage; }

private:
    std::string mWhere;
    std::string mMessage;
};

}  // namespace cg::formats
