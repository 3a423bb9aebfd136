#include "Errors.h"

#include <string>

#include <nlohmann/json.hpp>

#include "core/GraphDocument.h"
#include "formats/FormatError.h"

namespace py = pybind11;

namespace cg::python {

namespace {

/// The node id in a location such as "g.json:/nodes/render/params/width" (JSON pointer
/// escapes undone); empty when it names no node.
std::string nodeOf(const std::string& where)
{
    const auto at = where.find("/nodes/");
    if (at == std::string::npos) return "";
    const auto first = at + 7;
    const std::string token = where.substr(first, where.find('/', first) - first);
    std::string id;
    for (std::size_t i = 0; i < token.size(); ++i) {
        if (token[i] == '~' && i + 1 < token.size()) {
            id += token[i + 1] == '1' ? '/' : '~';
            ++i;
        } else {
            id += token[i];
        }
    }
    return id;
}

/// Which cloudgraph.errors class an InputError at a place in a graph is: a parameter's
/// value, or the graph itself. (The package raises a ParameterError about a parameter that
/// names an input file as a FileError: it knows the parameter's role.)
const char* classOf(const InputError& e)
{
    return e.where().find("/params/") != std::string::npos ? "ParameterError" : "GraphError";
}

void raise(const char* cls, const std::string& message, const std::string& where,
           const std::string& node, const py::dict& extra = {})
{
    py::object type = py::module_::import("cloudgraph.errors").attr(cls);
    py::object error = type(message);
    error.attr("where") = where;
    error.attr("node") = node.empty() ? py::object(py::none()) : py::object(py::str(node));
    for (auto item : extra) error.attr(item.first) = item.second;
    PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

void registerErrorTranslator()
{
    // NOLINTNEXTLINE(performance-unnecessary-value-param): pybind11's translator type.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const UnreadableGraph& e) {  // the file itself, not a place in it
            raise("FileError", e.what(), e.where(), "");
        } catch (const InputError& e) {
            raise(classOf(e), e.what(), e.where(), nodeOf(e.where()));
        } catch (const CookError& e) {
            py::dict extra;
            extra["input_fault"] = e.inputFault();
            raise("CookError", e.what(), "", e.nodeId(), extra);
        } catch (const Cancelled& e) {
            raise("Cancelled", "the cook was cancelled; nothing partial was cached", "", "");
        } catch (const formats::FormatError& e) {
            raise("FileError", e.what(), e.where(), "");
        } catch (const nlohmann::json::exception& e) {
            raise("GraphError", std::string("not JSON: ") + e.what(), "", "");
        }
    });
}

std::string pythonTraceback(py::error_already_set& e)
{
    std::string text;
    for (const py::handle line :
         py::module_::import("traceback").attr("format_exception")(e.type(), e.value(), e.trace()))
        text += line.cast<std::string>();
    return text;
}

}  // namespace cg::python
