//! Import benchmark: writes a ~1,000,000-node tet10 Abaqus deck (the block generator's 6-tet
//! split, 100×50×25 bricks) to the temp directory and times `flexbody::import::read_model` on
//! it. Not a test: run `cargo run --release -p flexbody-bench --bin import_bench [nx ny nz]`.

use std::io::{BufWriter, Write};
use std::time::Instant;

use flexbody::import::{read_model, ImportOptions};
use flexbody::model::generate::{block, BlockElement, BlockSpec};
use flexbody::model::Material;

fn main() -> std::io::Result<()> {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let n = match args.as_slice() {
        [x, y, z] => [*x, *y, *z],
        _ => [100, 50, 25],
    };
    let t = Instant::now();
    let m = block(&BlockSpec {
        n,
        size: [1.0, 0.5, 0.25],
        element: BlockElement::Tet10Six,
        material: Material::steel(),
    });
    let path =
        std::env::temp_dir().join(format!("flexbody_import_bench_{}.inp", std::process::id()));
    {
        let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(&path)?);
        writeln!(w, "** import benchmark: {n:?} bricks, 6 C3D10 each")?;
        writeln!(w, "*NODE, NSET=NALL")?;
        for node in &m.nodes {
            writeln!(
                w,
                "{}, {:?}, {:?}, {:?}",
                node.id, node.x[0], node.x[1], node.x[2]
            )?;
        }
        writeln!(w, "*ELEMENT, TYPE=C3D10, ELSET=SOLID")?;
        for e in &m.elements {
            write!(w, "{}", e.id)?;
            for &k in &e.nodes {
                write!(w, ", {}", m.nodes[k].id)?;
            }
            writeln!(w)?;
        }
        writeln!(w, "*NSET, NSET=X0")?;
        for chunk in m.node_sets["X0"].chunks(16) {
            let ids: Vec<String> = chunk.iter().map(|&k| m.nodes[k].id.to_string()).collect();
            writeln!(w, "{}", ids.join(", "))?;
        }
        writeln!(
            w,
            "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*DENSITY\n7850"
        )?;
        writeln!(
            w,
            "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n*BOUNDARY\nX0, 1, 3"
        )?;
    }
    let bytes = std::fs::metadata(&path)?.len();
    println!(
        "generated {} nodes, {} C3D10 in {:.2} s; wrote {} ({:.1} MB)",
        m.nodes.len(),
        m.elements.len(),
        t.elapsed().as_secs_f64(),
        path.display(),
        bytes as f64 / 1e6
    );
    drop(m);
    let mut best = f64::INFINITY;
    for run in 1..=3 {
        let t = Instant::now();
        let model = match read_model(&path, &ImportOptions::default()) {
            Ok(model) => model,
            Err(e) => {
                eprintln!("import failed: {e}");
                std::process::exit(1);
            }
        };
        let s = t.elapsed().as_secs_f64();
        best = best.min(s);
        println!(
            "run {run}: read_model {:.3} s ({} nodes, {} elements, {} spcs, {:.0} MB/s)",
            s,
            model.nodes.len(),
            model.elements.len(),
            model.spcs.len(),
            bytes as f64 / 1e6 / s
        );
    }
    println!("best of 3: {best:.3} s (target < 10 s)");
    std::fs::remove_file(&path)?;
    Ok(())
}
