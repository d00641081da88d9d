#pragma once
// ParaView files of a simulation (docs/results.md, "ParaView files"), written while it runs:
// per written sample one VTK XML PolyData file (.vtp) per body (BodyDrawing), one of the contact
// points and their loads if the system has contacts, and a multiblock file (.vtm) naming them
// after the bodies ("contacts" the last), and a ParaView data collection (.pvd)
// listing every finished .vtm with its time. Each file is written atomically and the .pvd is
// rewritten after every sample, so an interrupted run leaves a valid collection of every
// sample written so far.
//
// One block per body rather than one .vtp with a piece per body: VTK 9.1's XML PolyData reader
// (ParaView 5.10) misplaces the cells of a piece when the pieces before it lack one of its cell
// kinds (a rigid body's lines before a flexible body's polygons), and blocks carry the body
// names into ParaView's block tree.

#include <Eigen/Core>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "mbs/body_geometry.h"
#include "mbs/contact_load.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The .pvd collection beside results file `results`: the same folder and stem, ".pvd".
std::filesystem::path ParaviewCollectionFor(const std::filesystem::path& results);

/// Writes `body` as a VTK XML PolyData file of one piece (base64 appended data, Float64 points,
/// Int32 cells) to
/// `out`: point data `displacement` (3 components, [m] in W) and `displacement_magnitude` [m],
/// cell data `body_id`.
void WritePolyData(std::ostream& out, const BodyGeometry& body, int body_id);

/// Writes contact loads as a VTK XML PolyData file of one vertex per load: point data `force`
/// (3 components, [N] in W, the load on body A), `normal` (the unit normal from B to A),
/// `normal_force` (f . n [N]) and `contact_id`.
void WriteContactPolyData(std::ostream& out, const std::vector<ContactLoad>& loads);

/// Writes the ParaView files of a run of `system` (which must outlive the writer).
class ParaviewWriter {
 public:
  /// Files beside `collection` (<stem>.pvd), in the folder <stem>_vtk: per written sample k
  /// (k = 000000, 000001, ...) <stem>_<k>.vtm, <stem>_<k>_<b>.vtp per body b and, if the system
  /// has unilateral contacts or contact force elements, <stem>_<k>_contacts.vtp. Creates the
  /// folder, deletes the .vtm and .vtp files of an earlier run of the same stem and writes an
  /// empty collection. Every `every`-th sample offered to Record is written (every >= 1).
  /// Throws InputError naming the path if the folder or a file cannot be written.
  ParaviewWriter(const MultibodySystem& system, const std::filesystem::path& collection, int every = 1);

  /// Offers the sample at time t [s] with state y and the unilateral contacts' report of the
  /// output interval that ended there; writes it (its .vtp files, its .vtm, then the .pvd) if it
  /// is the first or an `every`-th one since. The contact loads: a unilateral contact k's
  /// (ContactStepResult::loads) with contact_id k, a contact force element i's (ContactLoads at
  /// y) with contact_id num_unilateral_contacts() + i. Returns whether it was written.
  bool Record(double t, const ConstVectorRef& y, const MoreauJeanStepReport& contacts = {});

  /// The samples written so far.
  long samples() const { return samples_; }
  const std::filesystem::path& collection() const { return collection_; }

 private:
  /// The multiblock file of written sample k and the .vtp of body b in it.
  std::filesystem::path SampleFile(long k) const;
  std::filesystem::path BodyFile(long k, int b) const;
  std::filesystem::path ContactFile(long k) const;
  /// The contact loads of a sample (see Record).
  std::vector<ContactLoad> ContactLoads(double t, const ConstVectorRef& y, const MoreauJeanStepReport& contacts) const;
  /// Rewrites the .pvd with every sample written so far (O(samples) bytes).
  void WriteCollection() const;

  const MultibodySystem& system_;
  std::filesystem::path collection_;
  std::filesystem::path folder_;
  std::string stem_;
  int every_;
  long offered_ = 0;
  std::vector<BodyDrawing> drawings_;
  bool draws_contacts_ = false;
  long samples_ = 0;
  std::string collection_entries_;  ///< the .pvd's DataSet lines so far
};

}  // namespace flexmbs::mbs
