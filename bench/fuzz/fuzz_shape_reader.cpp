// libFuzzer target for the shape-reading path (`vorohex mesh IN`, FreeCAD's BREP string):
// OCCT's STEP, BREP and IGES readers behind occ::read_solid and our checks after them
// (one closed, valid solid; healing, orientation; several solids glued). The first byte
// picks the entry point by its two lowest bits: 0 read_solid_from_brep_string, 1 a .step,
// 2 a .brep, 3 an .iges file; its bit 2 sets ReadOptions::several_solids (as `vorohex mesh`
// does). The other bytes are the text. A solid that reads is queried a little.
#include <IGESControl_Controller.hxx>
#include <STEPControl_Controller.hxx>

#include <sanitizer/lsan_interface.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "occ/shape_io.h"
#include "occ/solid.h"

namespace {

std::string temp_path(const char* extension) {
  static const std::string stem = (std::filesystem::temp_directory_path() /
                                   ("vorohex_fuzz_shape_" + std::to_string(::getpid())))
                                      .string();
  return stem + extension;
}

bool write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

// Cheap queries touching the topology maps and the geometry of the solid.
void use(const vorohex::occ::Solid& solid) {
  volatile double sink = solid.volume() + solid.diagonal() + solid.tolerance();
  sink = sink + solid.num_faces() + solid.num_edges() + solid.num_vertices();
  for (vorohex::core::EdgeId e : solid.edges())
    sink = sink + static_cast<double>(solid.edge_faces(e).size());
}

}  // namespace

// OCCT's STEP and IGES controllers are process-wide singletons whose one-time set-up loses
// a few hundred small blocks (MoniTool_TypedValue::AddEnum, IFSelect_Editor); make it here,
// with LeakSanitizer off, so that only leaks of later inputs are reported.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  __lsan::ScopedDisabler no_leak_check;
  STEPControl_Controller::Init();
  IGESControl_Controller::Init();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* text = reinterpret_cast<const char*>(data + 1);
  vorohex::occ::ReadOptions options;
  options.several_solids = (data[0] & 4) != 0;
  options.repair_time_limit = 5;  // well under libFuzzer's -timeout (run_fuzz.sh)
  vorohex::occ::ReadResult read;
  const int mode = data[0] & 3;
  if (mode == 0) {
    read = vorohex::occ::read_solid_from_brep_string(std::string(text, size - 1), options);
  } else {
    const std::string path = temp_path(mode == 1 ? ".step" : mode == 2 ? ".brep" : ".iges");
    if (!write_file(path, data + 1, size - 1)) return 0;
    read = vorohex::occ::read_solid(path, options);
    std::remove(path.c_str());
  }
  if (read.ok()) use(*read.solid);
  return 0;
}
