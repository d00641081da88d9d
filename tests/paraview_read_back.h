#pragma once
// ParaView files read back by readers independent of flexmbs: Python's strict XML parser and
// VTK's own vtkXMLMultiBlockDataReader (Debian's python3-vtk9, run by /usr/bin/python3) for
// every .vtm the .pvd collection lists and the .vtp files in it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>

namespace flexmbs::testing {

/// For a .pvd: per DataSet its `time`, `file` (a .vtm) and `blocks` as VTK's multiblock reader
/// reads them: per block its `name`, `points` (x, y, z rows), point data `displacement` (rows)
/// and `magnitude`, cell data `body_id` (empty where the block has none), every point data
/// array by name in `point_data`, and `cells` ([VTK cell type, point ids...]). Every
/// file is also parsed as strict XML. The script exits 1 on malformed XML and on any VTK error
/// or warning (VTK reports them through its output window rather than raising).
inline constexpr const char* kParaviewReadScript = R"(
import json, os, sys, xml.etree.ElementTree as ET
import vtk
from vtk.util.numpy_support import vtk_to_numpy
messages = vtk.vtkStringOutputWindow()
vtk.vtkOutputWindow.SetInstance(messages)
pvd = sys.argv[1]
root = ET.parse(pvd).getroot()
assert root.tag == 'VTKFile' and root.get('type') == 'Collection', root.tag
samples = []
for dataset in root.find('Collection').findall('DataSet'):
    path = os.path.join(os.path.dirname(pvd), dataset.get('file'))
    for block in ET.parse(path).getroot().iter('DataSet'):
        ET.parse(os.path.join(os.path.dirname(path), block.get('file')))
    reader = vtk.vtkXMLMultiBlockDataReader()
    reader.SetFileName(path)
    reader.Update()
    if messages.GetOutput():
        sys.exit('VTK: ' + messages.GetOutput())
    output = reader.GetOutput()
    def arrays(fields):
        return {fields.GetArrayName(i): vtk_to_numpy(fields.GetArray(i)).tolist()
                for i in range(fields.GetNumberOfArrays())}
    blocks = []
    for b in range(output.GetNumberOfBlocks()):
        data = output.GetBlock(b)
        point_data = arrays(data.GetPointData())
        cells = []
        for c in range(data.GetNumberOfCells()):
            ids = data.GetCell(c).GetPointIds()
            cells.append([data.GetCellType(c)] + [ids.GetId(k) for k in range(ids.GetNumberOfIds())])
        blocks.append({
            'name': output.GetMetaData(b).Get(vtk.vtkCompositeDataSet.NAME()),
            'points': vtk_to_numpy(data.GetPoints().GetData()).tolist() if data.GetPoints() else [],
            'displacement': point_data.get('displacement', []),
            'magnitude': point_data.get('displacement_magnitude', []),
            'body_id': arrays(data.GetCellData()).get('body_id', []),
            'point_data': point_data,
            'cells': cells})
    samples.append({'time': float(dataset.get('timestep')), 'file': dataset.get('file'), 'blocks': blocks})
json.dump(samples, open(sys.argv[2], 'w'))
)";

/// The collection `pvd` as kParaviewReadScript reads it (a JSON list, one entry per DataSet);
/// an empty list and a test failure if the script fails. `scratch` holds the script and its
/// output.
inline nlohmann::json ReadParaviewCollection(const std::filesystem::path& pvd, const std::filesystem::path& scratch) {
  const std::filesystem::path script = scratch / "paraview_read.py", out = scratch / "paraview_read.json";
  std::ofstream(script) << kParaviewReadScript;
  const int status =
      std::system(fmt::format("/usr/bin/python3 '{}' '{}' '{}'", script.string(), pvd.string(), out.string()).c_str());
  EXPECT_EQ(status, 0) << "VTK could not read " << pvd;
  if (status != 0) return nlohmann::json::array();
  std::ifstream in(out);
  return nlohmann::json::parse(in);
}

}  // namespace flexmbs::testing
