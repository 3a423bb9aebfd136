#include "Bindings.h"

#include <pybind11/stl.h>

#include "Document.h"
#include "Errors.h"
#include "ImageFiles.h"
#include "PythonNodes.h"
#include "Values.h"
#include "core/NodeDeclJson.h"

namespace py = pybind11;

namespace cg::python {

void defineModule(py::module_& m)
{
    m.doc() = "CloudGraph's engine; use the package cloudgraph, not this module.";
    registerErrorTranslator();
    bindValues(m);
    bindImageFiles(m);
    m.def("node_types_json", [] { return nodeTypesToJson(sharedRegistry()).dump(); });
    m.def("register_python_node", &registerPythonNode, py::arg("declaration_json"));

    py::class_<Document>(m, "Document")
        .def_static("load", &Document::load, py::arg("path"))
        .def_static("parse", &Document::parse, py::arg("text"), py::arg("name"),
                    py::arg("base_dir"))
        .def("to_json", &Document::toJson)
        .def("set_param", &Document::setParam, py::arg("node"), py::arg("param"), py::arg("value"))
        .def("replace", &Document::replace, py::arg("text"))
        .def("save", &Document::save, py::arg("path"))
        .def("cook", &Document::cook, py::arg("node"), py::arg("port"), py::arg("frame"),
             py::arg("cache"), py::arg("out"))
        .def("cancel", &Document::cancel)
        .def("last_report", &Document::lastReport)
        .def_property_readonly("name", &Document::name)
        .def_property_readonly("first_frame", &Document::firstFrame)
        .def_property_readonly("last_frame", &Document::lastFrame);
}

}  // namespace cg::python
