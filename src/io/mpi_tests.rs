//! MPI tests of the I/O layer, on 1 rank (a plain `cargo test` process is an MPI singleton) and
//! on 2 ranks (the test re-launches its own binary under `mpirun -n 2`, stack.md §8 pattern B).
//!
//! MPI is initialised once per process by [`world`] (with `Threading::Serialized`, and a lock
//! that serialises the tests that use it). Under `mpirun` the single test that runs finalises MPI
//! at its end and a panic on any rank aborts the whole job instead of hanging it.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use mpi::environment::Universe;
use mpi::topology::{Color, SimpleCommunicator};
use mpi::traits::{Communicator, CommunicatorCollectives, Root};

use super::hdf5_out::{OwnedMesh, ResultsFile, ResultsReader, StepInfo};
use super::redistribute::Redistribution;
use super::summary::{Phase, PhaseTimer, RunSummary};
use super::xdmf::parse_for_tests;
use super::IoError;

/// The MPI environment of this test process (`None` until initialised or after finalising).
static UNIVERSE: Mutex<Option<Universe>> = Mutex::new(None);
/// Serialises the tests that call MPI.
static MPI_LOCK: Mutex<()> = Mutex::new(());

/// The world communicator, with MPI initialised on first use, and the lock held by the caller.
fn world() -> (MutexGuard<'static, ()>, SimpleCommunicator) {
    let guard = MPI_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let mut universe = UNIVERSE.lock().unwrap_or_else(|e| e.into_inner());
    if universe.is_none() && !mpi::is_initialized() {
        let (u, _) = mpi::initialize_with_threading(mpi::Threading::Serialized).expect("MPI initialisation");
        *universe = Some(u);
    }
    (guard, SimpleCommunicator::world())
}

/// True inside a job started by `mpirun`.
fn under_mpirun() -> bool {
    std::env::var_os("OMPI_COMM_WORLD_SIZE").is_some()
}

/// Under `mpirun`: a panic on one rank aborts the whole job (otherwise the other ranks would
/// wait forever in the next collective call).
fn abort_on_panic() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        default(info);
        SimpleCommunicator::world().abort(101);
    }));
}

/// Finalises MPI (under `mpirun`, where exiting without `MPI_Finalize` is an error).
fn finalize() {
    let universe = UNIVERSE.lock().unwrap_or_else(|e| e.into_inner()).take();
    drop(universe);
}

/// Runs the test `name` of this binary on `n` ranks and checks that every rank passed.
fn launch(name: &str, n: usize, extra: &[&str]) -> String {
    let exe = std::env::current_exe().expect("test binary path");
    let output = crate::parallel::mpirun_command(n, 120)
        .arg(exe)
        .args([name, "--exact", "--nocapture", "--test-threads=1"])
        .args(extra)
        .output()
        .expect("mpirun (openmpi-bin) must be installed to run the MPI tests");
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "mpirun -n {n} {name} failed ({}):\n{stdout}\n{stderr}",
        output.status
    );
    assert_eq!(
        stdout.matches("1 passed").count(),
        n,
        "every rank must pass:\n{stdout}\n{stderr}"
    );
    stdout
}

/// A structured box of `nx × ny × nz` hex8 elements, unit spacing, Gmsh node order, ids offset
/// from the indices (nodes 101.., elements 1001..), two blocks split at half height.
fn box_mesh(nx: usize, ny: usize, nz: usize) -> crate::mesh::Mesh {
    use crate::mesh::{Block, Element, ElementKind, Mesh};
    let node = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    let mut mesh = Mesh::default();
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                mesh.coords.push([i as f64, j as f64 * 2.0, k as f64 * 0.5]);
                mesh.node_ids.push(101 + mesh.node_ids.len() as u64);
            }
        }
    }
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let nodes = [
                    node(i, j, k),
                    node(i + 1, j, k),
                    node(i + 1, j + 1, k),
                    node(i, j + 1, k),
                    node(i, j, k + 1),
                    node(i + 1, j, k + 1),
                    node(i + 1, j + 1, k + 1),
                    node(i, j + 1, k + 1),
                ];
                mesh.elements.push(Element {
                    id: 1001 + mesh.elements.len() as u64,
                    kind: ElementKind::Hex8,
                    nodes,
                    block: u32::from(2 * k >= nz),
                });
            }
        }
    }
    for name in ["foundation", "fill"] {
        mesh.blocks.push(Block {
            name: name.to_string(),
            kind: ElementKind::Hex8,
            orientation: None,
        });
    }
    mesh
}

/// Field value of item `i`, component `c`, step `s` (distinct for every triple).
fn value(i: u32, c: usize, s: u64) -> f64 {
    f64::from(i) * 1.0e-3 + c as f64 * 10.0 + s as f64 * 100.0 + (f64::from(i) * 0.37 + c as f64).sin()
}

/// Values of `items` (in the given order), `ncomp` per item.
fn values(items: &[u32], ncomp: usize, s: u64) -> Vec<f64> {
    items
        .iter()
        .flat_map(|&i| (0..ncomp).map(move |c| value(i, c, s)))
        .collect()
}

/// Fails at the first value that differs bitwise from the expected one.
fn assert_bitwise(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: number of values");
    if let Some(k) = (0..got.len()).find(|&k| got[k].to_bits() != want[k].to_bits()) {
        panic!("{what}: value {k} is {} instead of {}", got[k], want[k]);
    }
}

/// Scattered ownership: item `i` belongs to rank `i % size`; listed in reverse order so that the
/// order of a rank's list differs from the input order.
fn scattered(n: usize, rank: i32, size: i32) -> Vec<u32> {
    (0..n as u32)
        .rev()
        .filter(|&i| (i % size as u32) as i32 == rank)
        .collect()
}

/// A directory shared by all ranks of `comm`, named after rank 0's process id.
fn shared_dir(comm: &SimpleCommunicator, tag: &str) -> PathBuf {
    let mut pid = std::process::id();
    comm.process_at_rank(0).broadcast_into(&mut pid);
    let dir = std::env::temp_dir().join(format!("cfrd-io-{tag}-{pid}"));
    if comm.rank() == 0 {
        std::fs::create_dir_all(&dir).expect("test directory");
    }
    comm.barrier();
    dir
}

const QP: usize = 8;

/// Writes the standard test file on `comm` with the given node and element ownership.
fn write_case(
    comm: &SimpleCommunicator,
    path: &Path,
    mesh: &crate::mesh::Mesh,
    nodes: Vec<u32>,
    elements: Vec<u32>,
) {
    let owned = OwnedMesh::from_mesh(mesh, nodes.clone(), elements.clone());
    let mut out = ResultsFile::create(comm, path, "box test").expect("create");
    out.write_mesh(&owned).expect("mesh");
    for s in 1..=2u64 {
        let info = StepInfo {
            time: s as f64 * 0.25,
            stage: format!("stage {s}"),
            label: format!("increment {s}/2"),
        };
        assert_eq!(out.begin_step(info).expect("step"), s);
        out.write_node_field("displacement", "m", 3, &values(&nodes, 3, s))
            .expect("displacement");
        out.write_element_field("stress", "Pa", 6, &values(&elements, 6, s))
            .expect("stress");
        out.write_element_field("plastic", "-", 1, &values(&elements, 1, s))
            .expect("plastic");
    }
    // Checkpoint-like tables: integration-point states, row 8·e + q.
    let qp: Vec<u32> = elements
        .iter()
        .flat_map(|&e| (0..QP as u32).map(move |q| e * QP as u32 + q))
        .collect();
    let plan = Redistribution::new(comm, "integration points", (mesh.elements.len() * QP) as u64, &qp)
        .expect("qp plan");
    out.write_table("/checkpoint/qp_state", &plan, 5, &values(&qp, 5, 7))
        .expect("qp table");
    let flags: Vec<i64> = qp.iter().map(|&i| i64::from(i) * 3 - 7).collect();
    out.write_table("/checkpoint/qp_flag", &plan, 1, &flags)
        .expect("flag table");
    // A one-row table: every rank but 0 holds an empty block.
    let one: Vec<f64> = if comm.rank() == 0 {
        vec![42.0, 43.0]
    } else {
        Vec::new()
    };
    out.write_table_block("/checkpoint/scalars", 1, 2, &one)
        .expect("one-row table");
    out.close().expect("close");
}

/// Reads `path` on `comm` and checks every dataset against the analytic values.
fn check_case(comm: &SimpleCommunicator, path: &Path, mesh: &crate::mesh::Mesh) {
    let n_nodes = mesh.num_nodes() as u32;
    let n_elem = mesh.elements.len() as u32;
    let all_nodes: Vec<u32> = (0..n_nodes).collect();
    let all_elem: Vec<u32> = (0..n_elem).collect();
    let r = ResultsReader::open(comm, path).expect("open");
    assert_eq!(r.attr_string("/", "units").unwrap(), "SI");
    assert_eq!(r.attr_string("/", "scene").unwrap(), "box test");
    assert_eq!(r.attr::<u32>("/", "format_version").unwrap(), 1);
    assert_eq!(r.attr_string("/mesh", "block_names").unwrap(), "foundation\nfill");
    let (coords, nc) = r.read_all::<f64>("/mesh/coordinates").unwrap();
    assert_eq!(nc, 3);
    assert_bitwise(
        "coordinates",
        &coords,
        &mesh.coords.iter().flatten().copied().collect::<Vec<_>>(),
    );
    let (ids, _) = r.read_all::<i64>("/mesh/node_ids").unwrap();
    assert_eq!(ids, mesh.node_ids.iter().map(|&i| i as i64).collect::<Vec<_>>());
    let (topo, nc) = r.read_all::<i64>("/mesh/topology").unwrap();
    assert_eq!(nc, 8);
    let expect: Vec<i64> = mesh
        .elements
        .iter()
        .flat_map(|e| e.nodes.map(i64::from))
        .collect();
    assert_eq!(topo, expect);
    let (blocks, _) = r.read_all::<i64>("/mesh/element_block").unwrap();
    assert_eq!(
        blocks,
        mesh.elements
            .iter()
            .map(|e| i64::from(e.block))
            .collect::<Vec<_>>()
    );
    let (eids, _) = r.read_all::<i64>("/mesh/element_ids").unwrap();
    assert_eq!(
        eids,
        mesh.elements.iter().map(|e| e.id as i64).collect::<Vec<_>>()
    );

    let steps = r.steps().unwrap();
    assert_eq!(steps.len(), 2);
    for (k, (group, info)) in steps.iter().enumerate() {
        let s = k as u64 + 1;
        assert_eq!(group, &format!("/steps/{s:06}"));
        assert_eq!(info.time, s as f64 * 0.25);
        assert_eq!(info.stage, format!("stage {s}"));
        assert_eq!(r.attr::<u64>(group, "step").unwrap(), s);
        let (u, nc) = r.read_all::<f64>(&format!("{group}/displacement")).unwrap();
        assert_eq!(nc, 3);
        assert_bitwise("displacement", &u, &values(&all_nodes, 3, s));
        let (sig, nc) = r.read_all::<f64>(&format!("{group}/stress")).unwrap();
        assert_eq!(nc, 6);
        assert_bitwise("stress", &sig, &values(&all_elem, 6, s));
        assert_eq!(
            r.shape(&format!("{group}/plastic")).unwrap(),
            vec![n_elem as usize]
        );
        assert_eq!(
            r.attr_string(&format!("{group}/stress"), "center").unwrap(),
            "element"
        );
        assert_eq!(r.attr_string(&format!("{group}/stress"), "units").unwrap(), "Pa");
        assert_eq!(
            r.attr_string(&format!("{group}/displacement"), "components")
                .unwrap(),
            "x,y,z"
        );
    }
    let all_qp: Vec<u32> = (0..n_elem * QP as u32).collect();
    let (state, nc) = r.read_all::<f64>("/checkpoint/qp_state").unwrap();
    assert_eq!(nc, 5);
    assert_bitwise("qp_state", &state, &values(&all_qp, 5, 7));
    let (flags, _) = r.read_all::<i64>("/checkpoint/qp_flag").unwrap();
    assert_eq!(
        flags,
        all_qp.iter().map(|&i| i64::from(i) * 3 - 7).collect::<Vec<_>>()
    );
    assert_eq!(
        r.read_all::<f64>("/checkpoint/scalars").unwrap(),
        (vec![42.0, 43.0], 2)
    );

    // Each rank's block, and the owned rows under a different (scattered) ownership.
    let block = r.read_block::<f64>("/steps/000002/stress").unwrap();
    let rows: Vec<u32> = (block.rows.start as u32..block.rows.end as u32).collect();
    assert_bitwise("stress block", &block.values, &values(&rows, 6, 2));
    let mine = scattered(n_elem as usize, comm.rank(), comm.size());
    let plan = Redistribution::new(comm, "elements", u64::from(n_elem), &mine).unwrap();
    let back = r.read_owned::<f64>("/steps/000002/stress", &plan).unwrap();
    assert_bitwise("stress read back to owners", &back, &values(&mine, 6, 2));
    // Ghost-style reading: every rank asks for node 0 twice and the last node.
    let wanted = [0, n_nodes - 1, 0];
    let ghost = Redistribution::for_reading(comm, "nodes", u64::from(n_nodes), &wanted).unwrap();
    let got = r.read_owned::<f64>("/steps/000001/displacement", &ghost).unwrap();
    assert_bitwise("displacement read to ghosts", &got, &values(&wanted, 3, 1));

    check_xdmf(&r, &path.with_extension("xdmf"), path);
}

/// The XDMF file is well-formed and every `DataItem` names an existing dataset of that shape.
fn check_xdmf(r: &ResultsReader, xdmf: &Path, h5: &Path) {
    let text = std::fs::read_to_string(xdmf).expect("xdmf file");
    let elements = parse_for_tests(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let h5_name = h5.file_name().unwrap().to_string_lossy().into_owned();
    let items: Vec<_> = elements.iter().filter(|e| e.name == "DataItem").collect();
    assert_eq!(
        items.len(),
        2 * (2 + 3 + 3),
        "2 steps × (topology, geometry, 3 mesh + 3 step attributes)"
    );
    for item in items {
        let (file, dataset) = item.text.split_once(':').expect("file:dataset");
        assert_eq!(file, h5_name);
        let dims: Vec<usize> = item
            .attr("Dimensions")
            .map(|v| v.split(' ').map(|d| d.parse().unwrap()).collect())
            .unwrap();
        assert_eq!(r.shape(dataset).unwrap(), dims, "{dataset}");
    }
    assert_eq!(elements.iter().filter(|e| e.name == "Time").count(), 2);
}

/// Compares two files dataset by dataset (bitwise) and their attributes, except `n_ranks`.
fn assert_same_file(a: &ResultsReader, b: &ResultsReader) {
    let paths = a.dataset_paths().unwrap();
    assert_eq!(paths, b.dataset_paths().unwrap());
    assert!(paths.len() >= 13, "{paths:?}");
    for p in &paths {
        assert_eq!(a.shape(p).unwrap(), b.shape(p).unwrap(), "{p}");
        let is_int = ["ids", "topology", "block", "flag"].iter().any(|s| p.contains(s));
        if is_int {
            assert_eq!(
                a.read_all::<i64>(p).unwrap(),
                b.read_all::<i64>(p).unwrap(),
                "{p}"
            );
        } else {
            let (va, _) = a.read_all::<f64>(p).unwrap();
            let (vb, _) = b.read_all::<f64>(p).unwrap();
            assert_bitwise(p, &va, &vb);
        }
    }
    for attr in ["format", "units", "scene", "cfrd_version"] {
        assert_eq!(
            a.attr_string("/", attr).unwrap(),
            b.attr_string("/", attr).unwrap()
        );
    }
    assert_eq!(a.steps().unwrap(), b.steps().unwrap());
}

/// Ownership errors are reported on every rank, with the same text.
fn check_ownership_errors(comm: &SimpleCommunicator) {
    let (rank, size) = (comm.rank(), comm.size());
    let n = 10u64;
    let mut dup = scattered(n as usize, rank, size);
    if rank == size - 1 {
        dup.push(4);
    }
    let err = Redistribution::new(comm, "nodes", n, &dup).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, IoError::Ownership { .. }), "{text}");
    assert!(
        text.contains("1 item(s) owned by more than one rank (first: index 4)"),
        "{text}"
    );

    let mut missing = scattered(n as usize, rank, size);
    missing.retain(|&i| i != 3 && i != 8);
    let text = Redistribution::new(comm, "nodes", n, &missing)
        .unwrap_err()
        .to_string();
    assert!(
        text.contains("2 item(s) owned by no rank (first: index 3)"),
        "{text}"
    );

    let bad = if rank == 0 { vec![10] } else { Vec::new() };
    let err = Redistribution::new(comm, "nodes", n, &bad).unwrap_err();
    if rank == 0 {
        assert!(err.to_string().contains("index 10 is out of range"), "{err}");
    } else {
        assert!(
            matches!(&err, IoError::OnOtherRank { rank: 0, message } if message.contains("index 10")),
            "{err}"
        );
    }
}

/// A failed write leaves an existing file untouched and no temporary file; a successful one
/// replaces it.
fn check_temp_then_rename(comm: &SimpleCommunicator, dir: &Path, mesh: &crate::mesh::Mesh) {
    let path = dir.join("keep.h5");
    if comm.rank() == 0 {
        std::fs::write(&path, b"previous results").unwrap();
    }
    comm.barrier();
    let nodes = scattered(mesh.num_nodes(), comm.rank(), comm.size());
    let elements = scattered(mesh.elements.len(), comm.rank(), comm.size());
    {
        let mut out = ResultsFile::create(comm, &path, "failing").unwrap();
        assert!(out.temp_path().exists());
        out.write_mesh(&OwnedMesh::from_mesh(mesh, nodes.clone(), elements.clone()))
            .unwrap();
        out.begin_step(StepInfo {
            time: 1.0,
            stage: "s".into(),
            label: "l".into(),
        })
        .unwrap();
        // Rank 0 passes one value too few: every rank must fail, none may hang.
        let mut u = values(&nodes, 3, 1);
        if comm.rank() == 0 {
            u.pop();
        }
        let err = out.write_node_field("displacement", "m", 3, &u).unwrap_err();
        if comm.rank() != 0 {
            assert!(matches!(err, IoError::OnOtherRank { rank: 0, .. }), "{err}");
        }
        // A field without units agreement, and a mesh written twice, fail the same way.
        assert!(out
            .write_mesh(&OwnedMesh::from_mesh(mesh, nodes.clone(), elements.clone()))
            .is_err());
    }
    comm.barrier();
    assert_eq!(std::fs::read(&path).unwrap(), b"previous results");
    let leftovers: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("keep.h5.partial"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");

    let mut out = ResultsFile::create(comm, &path, "replacing").unwrap();
    out.write_mesh(&OwnedMesh::from_mesh(mesh, nodes, elements))
        .unwrap();
    out.close().unwrap();
    let r = ResultsReader::open(comm, &path).unwrap();
    assert_eq!(r.attr_string("/", "scene").unwrap(), "replacing");
    assert!(r.steps().unwrap().is_empty());
    let xdmf = std::fs::read_to_string(path.with_extension("xdmf")).unwrap();
    assert!(parse_for_tests(&xdmf).is_ok() && !xdmf.contains("Temporal"));
}

/// The collective parts of the run summary: per-rank peak memory and phase maxima.
fn check_summary(comm: &SimpleCommunicator) {
    let mut summary = RunSummary::new(comm, "box test");
    summary.gather_peak_memory(comm);
    assert_eq!(summary.ranks, comm.size() as u32);
    assert_eq!(summary.peak_memory_bytes_per_rank.len(), comm.size() as usize);
    assert!(
        summary.peak_memory_bytes_per_rank.iter().all(|&b| b > 1 << 20),
        "{summary:?}"
    );
    assert_eq!(
        summary.peak_memory_bytes,
        *summary.peak_memory_bytes_per_rank.iter().max().unwrap()
    );
    summary.gather_element_seconds(comm, 1.5 * (comm.rank() as f64 + 1.0));
    let expected: Vec<f64> = (0..comm.size()).map(|r| 1.5 * (r as f64 + 1.0)).collect();
    assert_eq!(summary.element_seconds_per_rank, expected);
    let mut timer = PhaseTimer::new();
    timer.add(
        Phase::Solve,
        std::time::Duration::from_millis(10 * (comm.rank() as u64 + 1)),
    );
    timer.add(Phase::Read, std::time::Duration::from_millis(7));
    let max = timer.seconds().max_over_ranks(comm);
    assert!(
        (max.solve - 0.010 * f64::from(comm.size())).abs() < 1e-12,
        "{max:?}"
    );
    assert!((max.read - 0.007).abs() < 1e-12 && max.output == 0.0, "{max:?}");
}

/// Every check, on whatever communicator size: scattered ownership against a reference written
/// by rank 0 alone with the whole mesh.
fn run_suite(world: &SimpleCommunicator, tag: &str) {
    let dir = shared_dir(world, tag);
    let mesh = box_mesh(4, 3, 5);
    let (rank, size) = (world.rank(), world.size());
    let scattered_path = dir.join("scattered.h5");
    write_case(
        world,
        &scattered_path,
        &mesh,
        scattered(mesh.num_nodes(), rank, size),
        scattered(mesh.elements.len(), rank, size),
    );
    let reference_path = dir.join("reference.h5");
    let alone = world
        .split_by_color(Color::with_value(rank))
        .expect("self communicator");
    if rank == 0 {
        let all_nodes = (0..mesh.num_nodes() as u32).collect();
        let all_elem = (0..mesh.elements.len() as u32).collect();
        write_case(&alone, &reference_path, &mesh, all_nodes, all_elem);
    }
    world.barrier();
    check_case(world, &scattered_path, &mesh);
    // Restart on a different rank count: the file written by one rank, read by all.
    check_case(world, &reference_path, &mesh);
    let a = ResultsReader::open(world, &scattered_path).unwrap();
    let b = ResultsReader::open(&alone, &reference_path).unwrap();
    assert_same_file(&a, &b);
    assert_eq!(a.attr::<u32>("/", "n_ranks").unwrap(), size as u32);
    assert_eq!(b.attr::<u32>("/", "n_ranks").unwrap(), 1);
    drop((a, b));
    check_ownership_errors(world);
    check_temp_then_rename(world, &dir, &mesh);
    check_summary(world);
    world.barrier();
    if rank == 0 {
        if std::env::var_os("CFRD_KEEP_TEST_FILES").is_some() {
            println!("test files kept in {}", dir.display());
        } else {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}

#[test]
fn one_rank_suite() {
    if under_mpirun() {
        return;
    }
    let (_guard, world) = world();
    assert_eq!(world.size(), 1);
    run_suite(&world, "np1");
}

#[test]
fn two_rank_suite() {
    if !under_mpirun() {
        launch("io::mpi_tests::two_rank_suite", 2, &[]);
        return;
    }
    abort_on_panic();
    let (guard, world) = world();
    assert_eq!(world.size(), 2);
    run_suite(&world, "np2");
    drop(world);
    drop(guard);
    finalize();
}

#[test]
fn three_rank_suite() {
    if !under_mpirun() {
        launch("io::mpi_tests::three_rank_suite", 3, &[]);
        return;
    }
    abort_on_panic();
    let (guard, world) = world();
    assert_eq!(world.size(), 3);
    run_suite(&world, "np3");
    drop(world);
    drop(guard);
    finalize();
}

/// Write time of a displacement field of about 1M nodes (`CFRD_BENCH_NODES` overrides the
/// count). Run in release:
/// `cargo test --release --lib io::mpi_tests::bench_displacement_write -- --ignored --nocapture`
/// and, on 2 ranks, `mpirun -n 2 <test binary> io::mpi_tests::bench_displacement_write --exact
/// --ignored --nocapture`.
#[test]
#[ignore = "benchmark; prints timings"]
fn bench_displacement_write() {
    let mpirun = under_mpirun();
    if mpirun {
        abort_on_panic();
    }
    let (guard, world) = world();
    let n: usize = std::env::var("CFRD_BENCH_NODES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1_000_000);
    let (rank, size) = (world.rank(), world.size());
    let dir = shared_dir(&world, "bench");
    let nodes = scattered(n, rank, size);
    let u = values(&nodes, 3, 1);
    let path = dir.join("bench.h5");
    let mut out = ResultsFile::create(&world, &path, "bench").unwrap();
    let plan = Redistribution::new(&world, "nodes", n as u64, &nodes).unwrap();
    let (mut best, mut best_move, mut best_write) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for k in 0..3 {
        world.barrier();
        let t0 = std::time::Instant::now();
        out.write_table(&format!("/u{k}"), &plan, 3, &u).unwrap();
        world.barrier();
        best = best.min(t0.elapsed().as_secs_f64());
        let t0 = std::time::Instant::now();
        let block = plan.to_block(&world, 3, &u).unwrap();
        world.barrier();
        best_move = best_move.min(t0.elapsed().as_secs_f64());
        let t0 = std::time::Instant::now();
        out.write_table_block(&format!("/v{k}"), n as u64, 3, &block)
            .unwrap();
        world.barrier();
        best_write = best_write.min(t0.elapsed().as_secs_f64());
    }
    let t0 = std::time::Instant::now();
    out.close().unwrap();
    let close = t0.elapsed().as_secs_f64();
    let r = ResultsReader::open(&world, &path).unwrap();
    let block = r.read_block::<f64>("/u2").unwrap();
    let rows: Vec<u32> = (block.rows.start as u32..block.rows.end as u32).collect();
    assert_bitwise("benchmark field", &block.values, &values(&rows, 3, 1));
    drop(r);
    if rank == 0 {
        println!(
            "BENCH ranks={size} nodes={n} displacement write (redistribute + collective write): best of 3 = {best:.3} s \
             ({:.0} MB/s); redistribution alone {best_move:.3} s, collective write alone {best_write:.3} s; \
             close {close:.3} s",
            (n * 24) as f64 / best / 1e6
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
    drop(world);
    drop(guard);
    if mpirun {
        finalize();
    }
}
