#pragma once
/// The engine's error types. Their class decides the CLI's exit code:
/// InputError (bad graph, parameter or file) exits 2, anything else exits 1. A node's cook
/// may also let a std::invalid_argument out (an algorithm's refusal, a file reader's
/// formats::FormatError): the evaluator makes it a CookError with inputFault() at the node.

#include <stdexcept>
#include <string>

namespace cg {

/// Bad input from the user: a graph, a parameter, a file. `where` names the place:
/// a JSON pointer ("/nodes/noise/params/beta"), "file:offset", or a node id.
class InputError : public std::runtime_error {
public:
    InputError(std::string where, const std::string& message)
        : std::runtime_error(where.empty() ? message : where + ": " + message),
          mWhere(std::move(where)),
          mMessage(message)
    {
    }
    const std::string& where() const { return mWhere; }
    const std::string& message() const { return mMessage; }

private:
    std::string mWhere;
    std::string mMessage;
};

/// Thrown from inside a cook when the evaluation was cancelled. Nothing partial is cached.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled") {}
};

/// A node's cook failed; wraps the node id, where in the graph (file and JSON pointer, e.g.
/// "g.json:/nodes/video/params/images") and what went wrong.
class CookError : public std::runtime_error {
public:
    CookError(const std::string& nodeId, const std::string& where, int frame,
              const std::string& what, bool inputFault)
        : std::runtime_error(where + ": node '" + nodeId + "' frame " + std::to_string(frame) +
                             ": " + what),
          mNodeId(nodeId),
          mInputFault(inputFault)
    {
    }
    const std::string& nodeId() const { return mNodeId; }
    /// True when the cause was bad input (an InputError or std::invalid_argument inside the
    /// node).
    bool inputFault() const { return mInputFault; }

private:
    std::string mNodeId;
    bool mInputFault;
};

}  // namespace cg
