// graspkit.Error for the engine's errors (with the file, line and element of the bad input), and
// the engine's warnings as Python warnings, one category per kind.

#include <cctype>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/host/invalid_setting.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

// Owned by the module (m.attr) for the interpreter's lifetime; these are borrowed pointers.
PyObject* error_type = nullptr;
std::map<WarningKind, PyObject*> warning_types;

std::mutex queue_mutex;
std::vector<Warning> queue;

// "unknown-element" -> "UnknownElementWarning"
std::string className(std::string_view kind) {
  std::string name;
  bool upper = true;
  for (char c : kind) {
    if (c == '-') {
      upper = true;
      continue;
    }
    name += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return name + "Warning";
}

}  // namespace

void bindErrors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_Exception);
  error.doc() =
      "Bad input: a malformed or missing file, an out-of-range value, a failed plugin.\n"
      "str(e) reads 'file:line: <element>: message'; e.file, e.line (0 when unknown), "
      "e.element and e.message hold the parts.";
  error_type = error.ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const host::InvalidSetting& e) {  // a bad argument, as Python names them
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Error& e) {
      py::object instance = py::reinterpret_borrow<py::object>(error_type)(e.what());
      instance.attr("file") = e.where().file;
      instance.attr("line") = e.where().line;
      instance.attr("element") = e.where().element;
      instance.attr("message") = e.message();
      PyErr_SetObject(error_type, instance.ptr());
    }
  });
}

void installWarningHandler(py::module_& m) {
  py::object base = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "graspkit.GraspkitWarning", "A warning from the engine; each kind has its own subclass.",
      PyExc_UserWarning, nullptr));
  m.attr("GraspkitWarning") = base;
  for (WarningKind kind : kWarningKinds) {
    const std::string name = className(nameOf(kind));
    const std::string qualified = "graspkit." + name;
    const std::string doc = fmt::format("graspkit's '{}' warnings (graspkit --no-warn {}).",
                                        nameOf(kind), nameOf(kind));
    py::object type = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc(qualified.c_str(), doc.c_str(), base.ptr(), nullptr));
    m.attr(name.c_str()) = type;
    warning_types[kind] = type.ptr();
  }
  setWarningHandler([](const Warning& warning) {
    std::lock_guard lock(queue_mutex);
    queue.push_back(warning);
  });
}

void flushWarnings() {
  std::vector<Warning> pending;
  {
    std::lock_guard lock(queue_mutex);
    pending.swap(queue);
  }
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const Warning& w = pending[i];
    // A filter that turns warnings into errors makes PyErr_WarnEx fail: raise that error.
    if (PyErr_WarnEx(warning_types.at(w.kind), describe(w).c_str(), 1) != 0)
      throw py::error_already_set();
  }
}

}  // namespace graspkit::python
