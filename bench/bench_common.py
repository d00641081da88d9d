"""Helpers shared by the benchmarks in bench/ (assembly_bench.py, reduce_bench.py).

* the steel of every benchmark body and the body file that names it;
* gmsh meshes of a box (a unit cube, or a beam-like bar) with physical groups on its end
  faces, tet10 (Mesh.SecondOrderIncomplete = 1), and the mesh size for a target DOF count;
* running a program under /usr/bin/time -v for its peak resident set size;
* single-threaded environments (BLAS and OpenMP), so that every program uses one core.

Runs under Debian's /usr/bin/python3 (python3-gmsh); gmsh is imported only when a mesh is made.
"""
import os
import re
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
PYTHON = "/usr/bin/python3"
TIME = "/usr/bin/time"
DEFAULT_FLEXMBS = os.path.join(ROOT, "build", "bin", "flexmbs")

# The benchmark material: steel [Pa, -, kg/m^3].
E, NU, RHO = 2.1e11, 0.3, 7850.0


def mesh_size_for(target_dofs, measured, volume=1.0):
    """Mesh size h whose DOF(h) = c(h) volume / h^3 is close to target_dofs.

    `measured`: (h, DOF h^3 / volume) pairs of meshes of the same shape; c(h) is fitted
    linearly in h (the surface layer of the mesh makes it grow with h), or taken constant
    from a single pair.
    """
    hs = [h for h, _ in measured]
    cs = [c for _, c in measured]
    n, mh, mc = len(hs), sum(hs) / len(hs), sum(cs) / len(cs)
    var = sum((h - mh) ** 2 for h in hs)
    slope = sum((h - mh) * (c - mc) for h, c in zip(hs, cs)) / var if n > 1 and var > 0 else 0.0
    per_volume = target_dofs / volume
    h = (mc / per_volume) ** (1.0 / 3.0)
    for _ in range(50):  # fixed point of h = (c(h) / target)^(1/3)
        h = max((mc + slope * (h - mh)) / per_volume, 1e-12) ** (1.0 / 3.0)
    return h


def make_box_msh(path, h, size=(1.0, 1.0, 1.0), end_faces=("clamp",)):
    """A box [0, size] as tet10 at uniform mesh size h, written to `path` (binary .msh).

    Physical volume 'body' (tag 1); physical surfaces named by `end_faces`: the first on the
    face x = 0 (tag 2), the second, if given, on the face x = size[0] (tag 3).
    """
    import gmsh
    lx, ly, lz = size
    eps = 1e-6 * max(size)
    gmsh.initialize([], False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("box")
        gmsh.model.occ.addBox(0, 0, 0, lx, ly, lz)
        gmsh.model.occ.synchronize()
        gmsh.model.addPhysicalGroup(3, [1], 1)
        gmsh.model.setPhysicalName(3, 1, "body")
        for k, (name, x) in enumerate(zip(end_faces, (0.0, lx))):
            faces = [t for _, t in gmsh.model.getEntitiesInBoundingBox(x - eps, -eps, -eps, x + eps, ly + eps,
                                                                       lz + eps, 2)]
            gmsh.model.addPhysicalGroup(2, faces, 2 + k)
            gmsh.model.setPhysicalName(2, 2 + k, name)
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
        gmsh.option.setNumber("Mesh.Binary", 1)
        gmsh.model.mesh.generate(3)
        gmsh.write(path)
    finally:
        gmsh.finalize()


def write_body_yaml(path, msh, name, node_sets=(), extra=""):
    """A body file for `msh` (same folder) in the benchmark steel, consistent mass; `extra`
    (YAML text, e.g. a reduction: section) is appended."""
    text = (f"name: {name}\ngeometry: {{file: {os.path.basename(msh)}}}\n"
            f"materials:\n  steel: {{youngs_modulus: {E}, poisson_ratio: {NU}, density: {RHO}}}\n"
            f"material: steel\nmass_matrix: consistent\n")
    if node_sets:
        text += f"node_sets: [{', '.join(node_sets)}]\n"
    with open(path, "w") as f:
        f.write(text + extra)


def single_thread_env(**extra):
    """os.environ with BLAS and OpenMP limited to one thread (plus `extra`)."""
    return dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", **extra)


def run_measured(cmd, env=None, cwd=None, timeout=None, memory_gb=None):
    """Runs cmd under /usr/bin/time -v, optionally with a wall-clock limit [s] and an address
    space limit [GB] (RLIMIT_AS, inherited by its children). Returns a dict: status ('ok',
    'timeout' or 'exit N'), stdout, stderr, peak_rss_mb (of the largest single process of
    the run, see timed_run), wall_s. On a timeout the whole process group is killed."""
    def limit():
        if memory_gb:
            import resource
            size = int(memory_gb * 2 ** 30)
            resource.setrlimit(resource.RLIMIT_AS, (size, size))
    start = time.perf_counter()
    p = subprocess.Popen([TIME, "-v"] + cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         cwd=cwd, start_new_session=True, preexec_fn=limit if memory_gb else None)
    try:
        out, err = p.communicate(timeout=timeout)
        status = "ok" if p.returncode == 0 else f"exit {p.returncode}"
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        status = "timeout"
    wall = time.perf_counter() - start
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", err)
    return {"status": status, "stdout": out, "stderr": err,
            "peak_rss_mb": int(m.group(1)) / 1024.0 if m else float("nan"), "wall_s": wall}


def timed_run(cmd, env=None, cwd=None, what="bench"):
    """Runs cmd under /usr/bin/time -v; returns (stdout, peak RSS in MB, wall s); a failure
    exits naming `what`.

    The peak RSS is that of the largest single process of the run (GNU time reports the
    maximum over the child and its waited-for descendants, not their sum).
    """
    r = run_measured(cmd, env=env, cwd=cwd)
    if r["status"] != "ok":
        sys.exit(f"{what}: failed ({r['status']}): {' '.join(cmd)}\n{r['stdout'][-1000:]}\n{r['stderr'][-2000:]}")
    return r["stdout"], r["peak_rss_mb"], r["wall_s"]


def require_executables(tools, what="bench"):
    for tool in tools:
        if not os.access(tool, os.X_OK):
            sys.exit(f"{what}: {tool} not found")
