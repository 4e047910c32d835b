// The Python module `aosuite._aosuite`: the one comparison (compare/comparison.hpp) on NumPy
// arrays and files, with the tolerance as keyword arguments by the names a suite's [tolerance]
// table uses (comparison::set_limit): the verdicts and messages are the CLI's, as nothing here
// decides one. python/aosuite/__init__.py is the module users import.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.hpp"
#include "compare/comparison.hpp"
#include "image/exr_file.hpp"
#include "image/image_io.hpp"

namespace py = pybind11;

namespace aosuite::python {
namespace {

// An array as the comparison takes a decoded file: uint8 as a canvas holds it (grey, grey and
// alpha, RGB and RGBA to RGBA), uint16 as a 16-bit PNG decodes (v / 65535, sRGB), float as
// linear samples. 16-bit and float images have 1 or 3 channels, as their files do.
Picture picture_of(const py::array& any, const std::string& name) {
  if (any.ndim() != 2 && any.ndim() != 3)
    throw py::value_error(name + ": an image array is height x width [x channels]");
  const int height = int(any.shape(0)), width = int(any.shape(1));
  const int channels = any.ndim() == 3 ? int(any.shape(2)) : 1;
  if (height <= 0 || width <= 0 || channels < 1 || channels > 4)
    throw py::value_error(name + ": an image array needs pixels and 1 to 4 channels");
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  Picture p;
  p.name = name, p.format = "array";
  if (py::isinstance<py::array_t<std::uint8_t>>(any)) {
    const auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>(any);
    const std::uint8_t* in = a.data();
    p.rgba = RgbaImage(width, height);
    unsigned char* out = p.rgba.data();
    for (std::size_t i = 0; i < pixels; ++i, in += channels, out += 4) {
      const bool grey = channels <= 2;
      out[0] = in[0], out[1] = in[grey ? 0 : 1], out[2] = in[grey ? 0 : 2];
      out[3] = channels == 2 ? in[1] : channels == 4 ? in[3] : 255;
    }
    return p;
  }
  const bool sixteen = py::isinstance<py::array_t<std::uint16_t>>(any);
  if (!sixteen && !py::isinstance<py::array_t<float>>(any) &&
      !py::isinstance<py::array_t<double>>(any)) {
    throw py::type_error(name + ": an image array holds uint8, uint16, float32 or float64");
  }
  if (channels != 1 && channels != 3)
    throw py::value_error(name + ": a 16-bit or float image has 1 or 3 channels");
  p.is_float = true;
  p.floats.width = width, p.floats.height = height, p.floats.channels = channels;
  p.floats.srgb = sixteen;
  p.floats.data.resize(pixels * std::size_t(channels));
  if (sixteen) {
    const auto a = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>(any);
    for (std::size_t i = 0; i < p.floats.data.size(); ++i)
      p.floats.data[i] = float(a.data()[i]) / 65535.0f;
  } else {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>(any);
    std::memcpy(p.floats.data.data(), a.data(), p.floats.data.size() * sizeof(float));
  }
  return p;
}

// Python values as a suite file writes them: True -> "true", 0.5 -> "0.5".
std::string limit_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return py::str(value).cast<std::string>();
}

comparison::Tolerance tolerance_of(const py::kwargs& limits, const std::vector<std::string>& gates,
                                   const std::vector<std::string>& float_gates,
                                   const std::vector<std::string>& metrics) {
  comparison::Tolerance t;
  for (const auto& [key, value] : limits) {
    try {
      comparison::set_limit(t, key.cast<std::string>(), limit_text(value));
    } catch (const std::invalid_argument& e) {
      throw py::value_error(e.what());
    }
  }
  try {
    for (const std::string& spec : gates) metric::add_gate_spec(t.gates, spec);
    for (const std::string& spec : float_gates) metric::add_gate_spec(t.float_gates, spec);
    for (const std::string& name : metrics) metric::gates_for(t.gates, metric::find(name));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return t;
}

py::array_t<std::uint8_t> array_of(const RgbaImage& image) {
  py::array_t<std::uint8_t> out({image.height(), image.width(), 4});
  std::memcpy(out.mutable_data(), image.data(), std::size_t(out.size()));
  return out;
}

py::dict result_of(const comparison::Comparison& c) {
  py::dict d;
  d["status"] = c.verdict == comparison::Verdict::kSame   ? "PASS"
                : c.verdict == comparison::Verdict::kWarn ? "WARN"
                                                          : "FAIL";
  d["message"] = c.message();
  d["failed"] = c.failed, d["warned"] = c.warned;
  d["identical"] = c.identical, d["comparable"] = c.comparable;
  d["actual_kind"] = c.actual_kind, d["expected_kind"] = c.expected_kind;
  d["mismatch_percent"] = c.mismatch_percent, d["mismatch_text"] = c.mismatch_text;
  d["max_channel_delta"] = c.max_channel_delta, d["differing_pixels"] = c.differing_pixels;
  d["mean_shift"] = c.mean_shift, d["mean_delta"] = c.mean_delta;
  d["largest"] = py::make_tuple(c.largest.value, c.largest.x, c.largest.y);
  py::dict metrics;
  for (const metric::Measurement& m : c.measured) {
    py::dict values;
    for (const metric::Value& v : m.values) values[py::str(v.key)] = v.value;
    metrics[py::str(m.metric)] = values;
  }
  d["metrics"] = metrics;
  d["diff"] = c.diff.empty() ? py::object(py::none()) : py::object(array_of(c.diff));
  return d;
}

// An image argument: a path (str or os.PathLike) is read as a file, anything else is an array.
struct Side {
  std::string name;
  std::vector<unsigned char> bytes;
  std::optional<Picture> picture;
  comparison::Input input() const {
    return picture ? comparison::Input::image(*picture) : comparison::Input::file(name, bytes);
  }
};

Side side_of(const py::object& image, const char* role) {
  Side s;
  if (py::isinstance<py::str>(image) || py::hasattr(image, "__fspath__")) {
    s.name = py::str(py::module_::import("os").attr("fspath")(image)).cast<std::string>();
    s.bytes = read_regular_file(s.name);
  } else {
    s.picture = picture_of(py::array::ensure(image), std::string("the ") + role + " array");
    s.name = s.picture->name;
  }
  return s;
}

py::dict compare(const py::object& actual, const py::object& expected,
                 const std::vector<std::string>& gates, const std::vector<std::string>& float_gates,
                 const std::vector<std::string>& metrics, bool diff, const py::kwargs& limits) {
  const comparison::Tolerance t = tolerance_of(limits, gates, float_gates, metrics);
  const Side a = side_of(actual, "actual"), e = side_of(expected, "expected");
  comparison::Options options;
  options.want_diff = diff;
  comparison::Comparison c;
  {
    py::gil_scoped_release unlocked;
    c = comparison::run(a.input(), e.input(), t, options);
  }
  return result_of(c);
}

// A golden written from an array, in its file's format, replacing the file only once complete:
// .png from uint8 (as RGBA), .exr from float.
void write_image(const std::string& file, const py::array& image) {
  const Picture p = picture_of(image, file);
  const std::string ext = std::filesystem::path(file).extension().string();
  if (ext == ".png" && !p.is_float) {
    write_png_rgba8(file, p.rgba.view());
  } else if (ext == ".exr" && p.is_float && !p.floats.srgb) {
    write_exr(file, p.floats.width, p.floats.height, p.floats.data.data(), p.floats.channels);
  } else {
    throw py::value_error(file + ": writes .png from a uint8 array and .exr from a float one");
  }
}

}  // namespace
}  // namespace aosuite::python

PYBIND11_MODULE(_aosuite, m) {
  m.doc() = "aosuite's one comparison (see the aosuite package)";
  m.def("compare", &aosuite::python::compare, py::arg("actual"), py::arg("expected"), py::kw_only(),
        py::arg("gates") = std::vector<std::string>(),
        py::arg("float_gates") = std::vector<std::string>(),
        py::arg("metrics") = std::vector<std::string>(), py::arg("diff") = false);
  m.def("write_image", &aosuite::python::write_image, py::arg("file"), py::arg("image"));
  m.attr("LIMIT_KEYS") = aosuite::comparison::kLimitKeys;
  m.attr("BUILD_AOSUITE") =
      AOSUITE_BUILD_BIN;  // this build's `aosuite`, the last resort of check()
  // A file that cannot be read or decoded: one line naming it, as the CLI says it.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const aosuite::FileError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}
