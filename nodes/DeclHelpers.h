#pragma once
/// Short constructors for parameter and port declarations, so a node file reads as a table.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/NodeDecl.h"
#include "nodes/io/WriterSupport.h"

namespace cg {

inline ParamDecl floatParam(std::string name, double def, std::string units, std::string doc,
                            std::optional<double> min = std::nullopt,
                            std::optional<double> max = std::nullopt)
{
    ParamDecl p;
    p.name = std::move(name);
    p.type = ParamType::Float;
    p.defaultValue = def;
    p.units = std::move(units);
    p.doc = std::move(doc);
    p.min = min;
    p.max = max;
    return p;
}

/// A vec3 parameter; min and max, when given, bound each component.
inline ParamDecl vec3Param(std::string name, Vec3 def, std::string units, std::string doc,
                           std::optional<double> min = std::nullopt,
                           std::optional<double> max = std::nullopt)
{
    ParamDecl p = floatParam(std::move(name), 0.0, std::move(units), std::move(doc), min, max);
    p.type = ParamType::Vector3;
    p.defaultValue = def;
    return p;
}

inline ParamDecl intParam(std::string name, std::int64_t def, std::string units, std::string doc,
                          std::optional<double> min = std::nullopt,
                          std::optional<double> max = std::nullopt)
{
    ParamDecl p = floatParam(std::move(name), 0.0, std::move(units), std::move(doc), min, max);
    p.type = ParamType::Int;
    p.defaultValue = def;
    return p;
}

/// A list of floats; min and max, when given, bound each element.
inline ParamDecl floatListParam(std::string name, std::vector<double> def, std::string units,
                                std::string doc, std::optional<double> min = std::nullopt,
                                std::optional<double> max = std::nullopt)
{
    ParamDecl p = floatParam(std::move(name), 0.0, std::move(units), std::move(doc), min, max);
    p.type = ParamType::FloatList;
    p.defaultValue = std::move(def);
    return p;
}

inline ParamDecl boolParam(std::string name, bool def, std::string doc)
{
    ParamDecl p;
    p.name = std::move(name);
    p.type = ParamType::Bool;
    p.defaultValue = def;
    p.doc = std::move(doc);
    return p;
}

inline ParamDecl stringParam(std::string name, std::string def, std::string doc,
                             std::vector<std::string> choices = {})
{
    ParamDecl p;
    p.name = std::move(name);
    p.type = ParamType::String;
    p.defaultValue = std::move(def);
    p.doc = std::move(doc);
    p.choices = std::move(choices);
    return p;
}

/// A file to read. The engine leaves it out of the key: the node's hashExtra must hash the
/// file's content instead.
inline ParamDecl inputFileParam(std::string name, std::string def, std::string doc)
{
    ParamDecl p = stringParam(std::move(name), std::move(def), std::move(doc));
    p.role = ParamRole::InputFile;
    return p;
}

/// A program the node runs, found on PATH by `name` unless the user says otherwise; see
/// ParamRole::Program.
inline ParamDecl programParam(std::string name, std::string programName, std::string doc)
{
    ParamDecl p = stringParam(std::move(name), std::move(programName), std::move(doc));
    p.role = ParamRole::Program;
    return p;
}

inline ParamDecl outputPathParam(std::string name, std::string def, std::string doc)
{
    ParamDecl p;
    p.name = std::move(name);
    p.type = ParamType::String;
    p.defaultValue = std::move(def);
    p.doc = std::move(doc);
    p.role = ParamRole::OutputPath;
    return p;
}

inline PortDecl port(std::string name, std::string type, std::string doc, bool optional = false)
{
    return PortDecl{std::move(name), std::move(type), std::move(doc), optional};
}

/// A writer: one input, an OutputPath parameter "file", an int parameter "every" (write on
/// every Nth frame from the start frame; see writesThisFrame), a Text output "files" with the
/// paths written; cooks on every run and per frame (#### in the name becomes the frame).
inline NodeDecl writerDecl(std::string type, std::string doc, PortDecl input,
                           std::string defaultFile)
{
    NodeDecl d;
    d.type = std::move(type);
    d.category = "io";
    d.doc = std::move(doc);
    d.writesFiles = true;
    d.frameDependent = true;
    d.inputs = {std::move(input)};
    d.outputs = {port("files", "Text", "the path written")};
    d.params = {
        outputPathParam("file", std::move(defaultFile), "file name, relative to --out"),
        intParam("every", 1, "frames",
                 "write frames start, start + every, start + 2 every, ...; skip the rest", 1)};
    d.framesWritten = [](const ParamSet& p, int start, int end) {
        return scheduledFrames(start, p.getInt("every"), start, end);
    };
    d.idleOnFrame = [](const ParamSet& p, int frame, int start) {
        return !scheduledFrame(start, p.getInt("every"), frame);
    };
    return d;
}

}  // namespace cg
