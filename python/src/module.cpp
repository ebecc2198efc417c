// neopipe._core: the C++ engine under the `neopipe` Python package (python/neopipe). The package's
// Python code gives the friendly signatures; this module is the thin layer over the libraries.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <string>
#include <string_view>

#include "bench/synthetic.hpp"
#include "calib/correspondence.hpp"
#include "nav/mapmaker/workspace.hpp"
#include "pipeline/compiled_graph.hpp"
#include "pipeline/executor.hpp"
#include "pipeline/io/frame_source.hpp"
#include "pipeline/kernel_registry.hpp"
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
  const auto ends_with = [&message](std::string_view tail) { return message.ends_with(tail); };
  return ends_with(": no such file") || ends_with(": no such file or directory") || ends_with(": no such image file") ||
         ends_with(": no such calibration file") || message.find("cannot open the graph spec") != std::string::npos;
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
    } catch (const pl::media::MediaError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());  // the codecs' plug-in, not the caller's file
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
  // The C++ side of that comparison inside this process: `neopipe bench`'s timing loop for its dots
  // case (bench/blob_bench.cpp, time_neopipe: the built-in blob graph on gray frames, submitted
  // cyclically, three frames of warm-up) on the arrays given. Timed in turn with the Python loop,
  // a busy machine slows both alike, which a separate `neopipe bench` process run seconds apart
  // cannot promise.
  m.def(
      "time_executor",
      [](const std::vector<py::array>& frames, int threshold, int threads, double min_seconds) {
        std::vector<cv::Mat> images;
        for (const auto& f : frames) images.push_back(neopipe::python::frame_view(f));
        if (images.empty()) throw py::value_error("time_executor: no frames");
        py::gil_scoped_release release;
        pl::BlobGraphOptions o;
        o.threshold = threshold;
        o.source = pl::PortType::gray8;
        pl::ExecutorOptions eo;
        eo.threads = threads;
        std::int64_t blobs = 0;
        pl::Executor ex(pl::compile(pl::blob_graph(o), pl::standard_kernels()), eo, [&](pl::FrameResult&& r) {
          blobs += static_cast<std::int64_t>(std::get<pl::BlobList>(r.outputs[0]).size());
        });
        const auto n = static_cast<std::int64_t>(images.size());
        std::int64_t i = 0;
        for (; i < 3; ++i) ex.submit(i, images[static_cast<std::size_t>(i % n)]);
        ex.finish();
        const std::int64_t start = i;
        using Clock = std::chrono::steady_clock;
        const auto t0 = Clock::now();
        const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
        do {
          for (int k = 0; k < 8; ++k, ++i) ex.submit(i, images[static_cast<std::size_t>(i % n)]);
        } while (elapsed() < min_seconds);
        ex.finish();
        return static_cast<double>(i - start) / elapsed();
      },
      py::arg("frames"), py::arg("threshold"), py::arg("threads"), py::arg("min_seconds"));

  neopipe::python::bind_reports(m);
}
