// The library record of an imported scan, shared by `palpation patient import`
// (cmd_patient.cpp) and the GUI's import dialog (through scan_import_job.h): one place
// decides what an imported patient is. Needs the patient library (QtSql builds).
#pragma once

#include <string>

#include "store/patient_library.h"
#include "scan/scan_import.h"

namespace palpation::app::scan {

using store::PatientRecord;

/// The library record of an imported scan: the mesh as .pmesh bytes, bulk tissue 19 kPa,
/// a press straight down over the highest point as its default finger path (what
/// `patient export` writes). Throws std::runtime_error when the mesh cannot be serialised.
PatientRecord imported_patient_record(const ImportResult& r, const std::string& name, const std::string& scan_file, double edge);

}  // namespace palpation::app::scan
