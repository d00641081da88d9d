#pragma once
// The ASCII SID file of SIMPACK's FEMBS ("SID_FEM"; Wallrapp 1994, "Standardization of flexible
// body modeling in multibody system codes"): an export of a reduced body for tools that read
// that format. What is written, the mapping of every block and what is left out:
// docs/sid-ascii.md.

#include <filesystem>

#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// Writes `body` to `path` as an ASCII SID file, atomically (a temporary renamed into place when
/// complete): a header line "<nodes> <modes> :No. nodes, No. modes: ...", then `part` /
/// `new modal` / `refmod` (mass, nelastq, ielastq) / `frame` (one `new node` per marker node:
/// rframe, origin, phi, psi, AP) / mdCM, J, Ct, Cr, Me, Gr, Ge, Oe, ksigma, Ke, De / `end modal` /
/// `end part`. Each Taylor block lists order, nrow, ncol, nq, nqn, structure and its non-zero
/// entries `m0(i,j)` and `m1(i,k,j)` (row i, modal coordinate k, column j; 1-based), each with
/// 17 significant digits and a Fortran 'D' exponent, so that every value reads back exactly.
/// J is written as the 6 x 1 column [xx, yy, zz, xy, xz, yz]; the 3 x 3n blocks Gr and Ge with
/// column (a - 1) n + k for axis a and mode k. J's order-2 term, the contact surfaces and the
/// separate stiffening matrices have no counterpart and are left out.
/// Precondition: CheckConsistent(body) holds and every invariant is finite (else InternalError).
/// Throws InputError naming `path` if the file cannot be written.
void WriteSidAscii(const std::filesystem::path& path, const ReducedBody& body);

}  // namespace flexmbs::sid
