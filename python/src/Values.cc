#include "Values.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <openvdb/openvdb.h>

#include "core/CoreData.h"
#include "formats/VdbFileWriter.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "nodes/data/Map2D.h"

namespace py = pybind11;

namespace cg::python {

namespace {

/// A read-only array of `shape` over `data`, which `owner` keeps alive.
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape,
               const std::shared_ptr<const void>& owner)
{
    // The capsule holds a copy of the shared pointer: the value lives as long as the array.
    auto* keep = new std::shared_ptr<const void>(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const void>*>(p); });
    py::array a(py::dtype::of<T>(), std::move(shape), data, base);
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

py::ssize_t count(std::size_t n) { return static_cast<py::ssize_t>(n); }

/// A read-only view of one of a frame's particle arrays, `width` values a row (1: a vector).
template <class T>
py::array rows(const algo::UninitArray<T>& a, std::size_t width,
               const std::shared_ptr<const void>& owner)
{
    if (width == 1) return view(a.data(), {count(a.size())}, owner);
    return view(a.data(), {count(a.size() / width), count(width)}, owner);
}

/// A value of a type without a NumPy form: its port type, for the user to see.
struct OpaqueValue {
    DataPtr value;
};

/// A map over the ground: values (ny, nx) and the cell size in metres.
struct MapValue {
    std::shared_ptr<const Map2DData> map;
};

/// A frame's cloud particles, materialised when first asked for.
struct ParticlesValue {
    std::shared_ptr<const CloudParticlesData> particles;
};

struct VolumeValue {
    std::shared_ptr<const FogVolumeData> volume;
};

MapValue newMap(const py::array_t<float, py::array::c_style | py::array::forcecast>& values,
                double cellSize)
{
    if (values.ndim() != 2)
        throw py::value_error("Map2D: values must be a 2D array (ny, nx), not " +
                              std::to_string(values.ndim()) + "D");
    const auto ny = static_cast<std::uint64_t>(values.shape(0));
    const auto nx = static_cast<std::uint64_t>(values.shape(1));
    std::vector<float> copy(values.data(), values.data() + values.size());
    try {
        checkMap2D(nx, ny, cellSize, copy);
    } catch (const std::runtime_error& e) {
        throw py::value_error(e.what());
    }
    return {std::make_shared<Map2DData>(static_cast<int>(nx), static_cast<int>(ny), cellSize,
                                        std::move(copy))};
}

py::array mapValues(const MapValue& m)
{
    return view(m.map->values.data(), {m.map->ny, m.map->nx}, m.map);
}

/// The active voxels as a dense array over their bounding box, x-major (index [i, j, k] is
/// voxel (i, j, k) + origin), and that origin.
py::tuple denseVolume(const VolumeValue& v)
{
    const openvdb::FloatGrid& grid = *v.volume->grid;
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty())
        return py::make_tuple(py::array_t<float>(std::vector<py::ssize_t>{0, 0, 0}),
                              std::array<int, 3>{0, 0, 0});
    const openvdb::Coord dim = box.dim();
    py::array_t<float> out(std::vector<py::ssize_t>{dim.x(), dim.y(), dim.z()});
    float* data = out.mutable_data();
    std::fill(data, data + out.size(), 0.0f);
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::CoordBBox b = it.getBoundingBox();
        for (auto c = b.begin(); c; ++c) {
            const openvdb::Coord d = *c - box.min();
            data[(static_cast<std::size_t>(d.x()) * dim.y() + d.y()) * dim.z() + d.z()] = *it;
        }
    }
    return py::make_tuple(out, std::array<int, 3>{box.min().x(), box.min().y(), box.min().z()});
}

}  // namespace

void bindValues(py::module_& m)
{
    py::class_<OpaqueValue>(m, "Value", "A node output without a NumPy form (its port type).")
        .def_property_readonly("type", [](const OpaqueValue& v) { return v.value->typeName(); })
        .def("__repr__",
             [](const OpaqueValue& v) { return "<cloudgraph.Value " + v.value->typeName() + ">"; });

    py::class_<MapValue>(m, "Map2D",
                         "A 2D map over the ground: values[iy, ix] for the cell at "
                         "[ix, ix + 1) x [iy, iy + 1) cell sizes from the origin.")
        .def(py::init(&newMap), py::arg("values"), py::arg("cell_size"),
             "a map of values (ny, nx), each in [0, 1], and a cell size in metres (copied)")
        .def_property_readonly("values", &mapValues, "read-only float32 array (ny, nx)")
        .def_property_readonly(
            "cell_size", [](const MapValue& v) { return v.map->cellSize; }, "metres")
        .def(
            "__array__",
            [](const MapValue& v, const py::object& dtype) {
                py::array a = mapValues(v);
                return dtype.is_none() ? a : a.attr("astype")(dtype).cast<py::array>();
            },
            py::arg("dtype") = py::none());

    py::class_<ParticlesValue>(m, "CloudParticles", "A frame's cloud particles (Sec. 5.2).")
        .def("__len__", [](const ParticlesValue& p) { return p.particles->size(); })
        .def_property_readonly(
            "positions",
            [](const ParticlesValue& p) { return rows(p.particles->positions(), 3, p.particles); },
            "read-only float32 array (n, 3), metres")
        .def_property_readonly(
            "levels",
            [](const ParticlesValue& p) { return rows(p.particles->levels(), 1, p.particles); },
            "read-only uint8 array (n,): the recursive level L")
        .def_property_readonly(
            "sources",
            [](const ParticlesValue& p) { return rows(p.particles->sources(), 1, p.particles); },
            "read-only uint32 array (n,): the source record of each particle")
        .def_property_readonly(
            "copy_origins",
            [](const ParticlesValue& p) {
                return rows(p.particles->copyOrigins(), 3, p.particles);
            },
            "read-only float32 array (sources, 3): where each source's copy stands");

    py::class_<VolumeValue>(m, "FogVolume", "A sparse OpenVDB fog volume (grid 'density').")
        .def_property_readonly("voxel_size",
                               [](const VolumeValue& v) { return v.volume->grid->voxelSize()[0]; })
        .def_property_readonly(
            "active_voxel_count",
            [](const VolumeValue& v) {
                return static_cast<std::uint64_t>(v.volume->grid->activeVoxelCount());
            })
        .def_property_readonly(
            "bbox",
            [](const VolumeValue& v) {
                const auto b = v.volume->grid->evalActiveVoxelBoundingBox();
                return py::make_tuple(std::array<int, 3>{b.min().x(), b.min().y(), b.min().z()},
                                      std::array<int, 3>{b.max().x(), b.max().y(), b.max().z()});
            },
            "the active voxels' index box, ((i, j, k) min, (i, j, k) max), inclusive")
        .def("to_dense", &denseVolume,
             "(array, origin): float32 array over the active box, x-major, and its first voxel")
        .def(
            "to_vdb",
            [](const VolumeValue& v, const std::string& path) {
                py::gil_scoped_release release;
                formats::writeVdbFile(path, v.volume->grid, "cloudgraph python", std::nullopt);
            },
            py::arg("path"), "writes the grid as a .vdb file, atomically");
}

py::object toPython(const DataPtr& value)
{
    if (auto f = std::dynamic_pointer_cast<const FloatData>(value)) return py::float_(f->value);
    if (auto i = std::dynamic_pointer_cast<const IntData>(value)) return py::int_(i->value);
    if (auto t = std::dynamic_pointer_cast<const TextData>(value)) return py::str(t->value);
    if (auto a = std::dynamic_pointer_cast<const FloatArrayData>(value))
        return view(a->values.data(), {count(a->values.size())}, a);
    if (auto image = std::dynamic_pointer_cast<const ImageData>(value))
        return view(image->rgba.data(), {image->height, image->width, 4}, image);
    if (auto map = std::dynamic_pointer_cast<const Map2DData>(value))
        return py::cast(MapValue{map});
    if (auto p = std::dynamic_pointer_cast<const CloudParticlesData>(value))
        return py::cast(ParticlesValue{p});
    if (auto v = std::dynamic_pointer_cast<const FogVolumeData>(value))
        return py::cast(VolumeValue{v});
    return py::cast(OpaqueValue{value});
}

namespace {

[[noreturn]] void refuse(const std::string& what, const std::string& type, const std::string& why)
{
    throw std::invalid_argument(what + " (" + type + "): " + why);
}

/// The value a wrapper class (Map2D, CloudParticles, FogVolume, Value) holds, or null.
DataPtr wrapped(const py::handle& value)
{
    if (py::isinstance<MapValue>(value)) return value.cast<const MapValue&>().map;
    if (py::isinstance<ParticlesValue>(value)) return value.cast<const ParticlesValue&>().particles;
    if (py::isinstance<VolumeValue>(value)) return value.cast<const VolumeValue&>().volume;
    if (py::isinstance<OpaqueValue>(value)) return value.cast<const OpaqueValue&>().value;
    return nullptr;
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

DataPtr imageFrom(const py::handle& value, const std::string& what)
{
    const FloatArray a = FloatArray::ensure(value);
    if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 ||
        a.shape(1) < 1)
        refuse(what, "Image", "needs a float array (height, width, 3 or 4)");
    const auto h = static_cast<std::size_t>(a.shape(0));
    const auto w = static_cast<std::size_t>(a.shape(1));
    const auto channels = static_cast<std::size_t>(a.shape(2));
    std::vector<float> rgba(h * w * 4, 1.0f);  // alpha 1 where only RGB is given
    const float* in = a.data();
    for (std::size_t i = 0; i < h * w; ++i)
        for (std::size_t c = 0; c < channels; ++c) rgba[4 * i + c] = in[channels * i + c];
    return std::make_shared<ImageData>(static_cast<int>(w), static_cast<int>(h), std::move(rgba));
}

}  // namespace

DataPtr fromPython(const py::handle& value, const std::string& type, const std::string& what)
{
    if (DataPtr held = wrapped(value)) {
        if (held->typeName() != type) refuse(what, type, "got a " + held->typeName());
        return held;
    }
    if (type == "Float") {
        if (!py::hasattr(value, "__float__")) refuse(what, type, "needs a number");
        const double v = PyFloat_AsDouble(value.ptr());
        if (v == -1.0 && PyErr_Occurred()) {
            // An int past a double's range (OverflowError), or a __float__ that raised.
            const py::error_already_set error;
            refuse(what, type, "cannot be a float: " + std::string(error.what()));
        }
        if (!std::isfinite(v)) refuse(what, type, "is not finite");
        return std::make_shared<FloatData>(v);
    }
    if (type == "Int") {
        if (!py::hasattr(value, "__index__")) refuse(what, type, "needs an integer");
        const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
        if (!index) throw py::error_already_set();
        int overflow = 0;
        const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
        if (overflow != 0)
            refuse(what, type,
                   "an integer of " + std::string(py::str(index.attr("bit_length")())) +
                       " bits is outside the signed 64-bit range");
        if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
        return std::make_shared<IntData>(static_cast<std::int64_t>(v));
    }
    if (type == "Text") {
        if (!py::isinstance<py::str>(value)) refuse(what, type, "needs a str");
        return std::make_shared<TextData>(value.cast<std::string>());
    }
    if (type == "FloatArray") {
        const FloatArray a = FloatArray::ensure(value);
        if (!a || a.ndim() != 1) refuse(what, type, "needs a 1D float array");
        return std::make_shared<FloatArrayData>(std::vector<float>(a.data(), a.data() + a.size()));
    }
    if (type == "Image") return imageFrom(value, what);
    refuse(what, type,
           "got a " + std::string(py::str(value.get_type().attr("__name__"))) +
               (type == "Map2D" ? "; make one with cloudgraph.Map2D(values, cell_size)"
                                : "; a Python node can pass on such a value it was given"));
}

}  // namespace cg::python
