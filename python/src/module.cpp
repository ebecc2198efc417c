// neopipe._core: the C++ engine under the `neopipe` Python package (python/neopipe). The package's
// Python code gives the friendly signatures; this module is the thin layer over the libraries.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bench/synthetic.hpp"
#include "calib/correspondence.hpp"
#include "nav/mapmaker/workspace.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/media/media.hpp"
#include "pipeline/source_location.hpp"
#include "python/src/engine.hpp"
#include "python/src/frames.hpp"
#include "python/src/reports.hpp"
#include "sim/world.hpp"

namespace py = pybind11;
namespace pl = neopipe::pipeline;
using neopipe::python::Graph;
using neopipe::python::Stream;

namespace {

// A file that is not there is FileNotFoundError, whoever noticed it; the message stays the library's
// (the CLI's) one line.
bool names_missing_file(const std::string& message) {
  return message.find("no such file") != std::string::npos ||
         message.find("no such calibration file") != std::string::npos ||
         message.find("cannot open the graph spec") != std::string::npos;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "neopipe's C++ engine; use the `neopipe` package, which wraps it.";
  neopipe::python::register_blob_dtype();

  // Exception classes live in the module (not as globals of ours): the translator finds them there.
  py::object graph_error = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "neopipe.GraphError", "A graph spec that does not validate (file:line:column: message).", PyExc_ValueError,
      nullptr));
  m.attr("GraphError") = graph_error;
  py::register_exception_translator([](std::exception_ptr p) {
    const auto raise = [](PyObject* type, const char* what) {
      PyErr_SetString(names_missing_file(what) ? PyExc_FileNotFoundError : type, what);
    };
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (ValueError, StopIteration, ...): its translator knows them
    } catch (const pl::GraphError& e) {
      const py::object cls = py::module_::import("neopipe._core").attr("GraphError");
      raise(cls.ptr(), e.what());
    } catch (const pl::io::SourceError& e) {
      raise(PyExc_RuntimeError, e.what());
    } catch (const neopipe::sim::WorldError& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const neopipe::calib::CalibrationError& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const neopipe::nav::mapmaker::MapError& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const std::invalid_argument& e) {
      raise(PyExc_ValueError, e.what());
    } catch (const std::runtime_error& e) {
      raise(PyExc_RuntimeError, e.what());
    }
  });

  py::class_<Graph>(m, "Graph")
      .def_static(
          "load", [](const std::string& path) { return std::make_unique<Graph>(pl::load_graph_spec(path)); },
          py::arg("path"))
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& origin) {
            return std::make_unique<Graph>(pl::parse_graph_spec(text, origin));
          },
          py::arg("text"), py::arg("origin") = "<yaml text>")
      .def_static(
          "blobs",
          [](const py::object& threshold, int connectivity, const std::string& source) {
            pl::BlobGraphOptions o = neopipe::python::builtin_options(threshold, connectivity);
            const auto type = pl::port_type_from_string(source);
            if (!type || (*type != pl::PortType::gray8 && *type != pl::PortType::bgr8)) {
              throw py::value_error("source '" + source + "': must be 'gray8' or 'bgr8'");
            }
            o.source = *type;
            return std::make_unique<Graph>(pl::blob_graph(o));
          },
          py::arg("threshold") = py::none(), py::arg("connectivity") = 8, py::arg("source") = "gray8")
      .def("process", &Graph::process, py::arg("frame"))
      .def("process_outputs", &Graph::process_outputs, py::arg("frame"))
      .def("reset", &Graph::reset)
      .def_property_readonly("name", &Graph::name)
      .def_property_readonly("origin", &Graph::origin)
      .def_property_readonly("outputs", &Graph::output_names)
      .def_property_readonly("source_type", &Graph::source_type)
      .def_property_readonly("frames", &Graph::frames)
      .def_property_readonly("_last_frame_address", &Graph::last_frame_address);

  py::class_<Stream>(m, "Stream")
      .def("__iter__", [](Stream& s) -> Stream& { return s; })
      .def("__next__", &Stream::next)
      .def_property_readonly("description", &Stream::description);

  const auto config = [](const Graph* graph, const py::object& threshold, int connectivity, int threads,
                         const std::string& calib, double height) {
    neopipe::python::StreamConfig c;
    if (graph) c.spec = graph->spec();
    c.builtin = neopipe::python::builtin_options(threshold, connectivity);
    c.threads = threads;
    c.calib = calib;
    c.height = height;
    return c;
  };
  m.def(
      "stream_frames",
      [config](const Graph* graph, const py::object& threshold, int connectivity, int threads, const std::string& calib,
               double height, const py::iterable& frames) {
        return std::make_unique<Stream>(config(graph, threshold, connectivity, threads, calib, height),
                                        py::iter(frames));
      },
      py::arg("graph"), py::arg("threshold"), py::arg("connectivity"), py::arg("threads"), py::arg("calib"),
      py::arg("height"), py::arg("frames"));
  m.def(
      "stream_files",
      [config](const Graph* graph, const py::object& threshold, int connectivity, int threads, const std::string& calib,
               double height, const std::vector<std::string>& inputs) {
        return std::make_unique<Stream>(config(graph, threshold, connectivity, threads, calib, height), inputs);
      },
      py::arg("graph"), py::arg("threshold"), py::arg("connectivity"), py::arg("threads"), py::arg("calib"),
      py::arg("height"), py::arg("inputs"));
  m.def("blob_dtype", [] { return py::dtype::of<neopipe::python::BlobRow>(); });
  m.def("world_blob_dtype", &neopipe::python::world_blob_dtype);
  // `neopipe bench`'s generated frames (bench/synthetic.hpp), so python/bench_python.py times the
  // very frames the C++ figure is measured on.
  m.def(
      "dots_frame",
      [](int width, int height, int count, std::uint64_t seed) {
        if (width <= 0 || height <= 0 || count < 0) throw py::value_error("dots_frame: positive size, count >= 0");
        return neopipe::python::image_array(neopipe::bench::make_dots_frame({width, height}, count, seed));
      },
      py::arg("width"), py::arg("height"), py::arg("count") = 100, py::arg("seed") = 17);
  m.attr("dots_threshold") = neopipe::bench::dots_threshold;

  neopipe::python::bind_reports(m);
}
