#include "core/io/vtk_util.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstring>
#include <mutex>
#include <sstream>

#include "core/util/error.h"

namespace facehex::io {

namespace {

// VTK's message switches are process-global: serialize our VTK I/O so two reads cannot flip them under each other.
std::mutex& vtk_io_mutex() {
  static std::mutex m;
  return m;
}

// "ERROR: In .../vtkXMLReader.cxx, line 42\nvtkXMLUnstructuredGridReader (0x5581): Error parsing input file.\n\n"
// -> "Error parsing input file."
std::string first_message(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line.find(": In ") != std::string::npos) continue;  // "ERROR: In file, line n"
    const size_t colon = line.find("): ");
    if (colon != std::string::npos) line = line.substr(colon + 3);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
    if (!line.empty()) return line;
  }
  return {};
}

// The legacy reader reports damaged data ("Error reading binary data!") as a mere warning and carries on with a
// half-filled grid: warnings that speak of an error count as errors.
bool is_error_warning(const char* text) { return text && std::strstr(text, "rror") != nullptr; }

// Collects the messages of the objects inside an algorithm (the legacy reader's data parsing, the XML parser, the
// executive), which report through the global output window rather than through the algorithm.
class CaptureWindow : public vtkOutputWindow {
 public:
  // What vtkStandardNewMacro would define; vtkTypeMacro is left out as nothing asks this class for its type.
  static CaptureWindow* New() {
    auto* window = new CaptureWindow;
    window->InitializeObjectBase();
    return window;
  }

  void DisplayText(const char*) override {}  // plain text and debug output: dropped
  void DisplayErrorText(const char* text) override { keep(text); }
  void DisplayWarningText(const char* text) override {
    if (is_error_warning(text)) keep(text);
  }
  void DisplayGenericWarningText(const char* text) override {
    if (is_error_warning(text)) keep(text);
  }
  void keep(const char* text) {
    if (error.empty() && text) error = text;
  }
  std::string error;
};

void on_error(vtkObject*, unsigned long, void* client_data, void* call_data) {
  static_cast<CaptureWindow*>(client_data)->keep(call_data ? static_cast<const char*>(call_data) : "unknown error");
}

void on_warning(vtkObject* caller, unsigned long event, void* client_data, void* call_data) {
  if (is_error_warning(static_cast<const char*>(call_data))) on_error(caller, event, client_data, call_data);
}

}  // namespace

void run_vtk(const std::string& path, const std::string& what, vtkAlgorithm* algorithm,
             const std::function<int()>& action) {
  std::lock_guard<std::mutex> lock(vtk_io_mutex());
  vtkNew<CaptureWindow> capture;
  vtkNew<vtkCallbackCommand> error_observer, warning_observer;
  error_observer->SetCallback(on_error);
  error_observer->SetClientData(capture.Get());
  warning_observer->SetCallback(on_warning);
  warning_observer->SetClientData(capture.Get());
  int ok = 1;
  {
    // For the duration of the action: the algorithm's own messages go to the observers, everything else to the
    // capture window; messages are on (the caller may have switched them off, but we need them to see failures),
    // and vtkLogger, which VTK 9 also feeds every message, prints nothing to stderr. The guard puts everything back
    // however the action ends. vtkLogger cannot tell its stderr level, only the most verbose of its outputs, which
    // is the stderr level unless someone added a log file or callback.
    struct Guard {
      vtkAlgorithm* algorithm;
      unsigned long error_tag, warning_tag;
      vtkSmartPointer<vtkOutputWindow> window = vtkOutputWindow::GetInstance();
      int display = vtkObject::GetGlobalWarningDisplay();
      vtkLogger::Verbosity verbosity = vtkLogger::GetCurrentVerbosityCutoff();
      ~Guard() {
        algorithm->RemoveObserver(error_tag);
        algorithm->RemoveObserver(warning_tag);
        vtkOutputWindow::SetInstance(window);
        vtkObject::SetGlobalWarningDisplay(display);
        vtkLogger::SetStderrVerbosity(verbosity);
      }
    } guard{algorithm, algorithm->AddObserver(vtkCommand::ErrorEvent, error_observer),
            algorithm->AddObserver(vtkCommand::WarningEvent, warning_observer)};
    vtkOutputWindow::SetInstance(capture);
    vtkObject::GlobalWarningDisplayOn();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    ok = action ? action() : algorithm->GetExecutive()->Update();
  }

  std::string message = first_message(capture->error);
  const unsigned long code = algorithm->GetErrorCode();
  if (message.empty() && code != vtkErrorCode::NoError) message = vtkErrorCode::GetStringFromErrorCode(code);
  if (message.empty() && !ok) message = "VTK reported a failure (damaged or unsupported file?)";
  if (!message.empty()) throw Error(path, what + " failed: " + message);
}

void vtk_arrays_to_matrices(const std::string& path, vtkFieldData* data, int rows,
                            std::map<std::string, Eigen::MatrixXd>* out) {
  if (!data) return;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* array = data->GetArray(i);  // null for string arrays
    if (!array) continue;
    const std::string name = array->GetName() && *array->GetName() ? array->GetName() : "array" + std::to_string(i);
    if (rows >= 0 && array->GetNumberOfTuples() != rows) {
      throw Error(path, "data array '" + name + "' has " + std::to_string(array->GetNumberOfTuples()) +
                            " values, expected " + std::to_string(rows) + " (truncated file?)");
    }
    const int k = array->GetNumberOfComponents(), n = static_cast<int>(array->GetNumberOfTuples());
    Eigen::MatrixXd m(n, k);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < k; ++c) m(r, c) = array->GetComponent(r, c);
    (*out)[name] = std::move(m);
  }
}

void matrices_to_vtk_arrays(const std::map<std::string, Eigen::MatrixXd>& arrays, vtkFieldData* out,
                            const std::set<std::string>& single_precision) {
  for (const auto& [name, m] : arrays) {
    vtkSmartPointer<vtkDataArray> array;
    if (single_precision.count(name))
      array = vtkSmartPointer<vtkFloatArray>::New();
    else
      array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(static_cast<int>(m.cols()));
    array->SetNumberOfTuples(m.rows());
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) array->SetComponent(r, static_cast<int>(c), m(r, c));
    out->AddArray(array);
  }
}

SurfaceMesh triangles_of(const std::string& subject, vtkPolyData* poly) {
  SurfaceMesh s;
  s.V.resize(poly->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double p[3];
    poly->GetPoint(i, p);
    s.V.row(i) << p[0], p[1], p[2];
  }
  vtkCellArray* polys = poly->GetPolys();
  s.F.resize(polys->GetNumberOfCells(), 3);
  vtkNew<vtkIdList> ids;
  for (vtkIdType f = 0; f < polys->GetNumberOfCells(); ++f) {
    polys->GetCellAtId(f, ids);
    if (ids->GetNumberOfIds() != 3) throw Error(subject, "polygon " + std::to_string(f) + " is not a triangle");
    s.F.row(f) << static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)), static_cast<int>(ids->GetId(2));
  }
  return s;
}

}  // namespace facehex::io
