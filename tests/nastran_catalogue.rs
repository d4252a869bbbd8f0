//! Issue 44, part A, through the CLI: a structural deck and the same deck with appended
//! blocks of aeroelastic, dynamic-response, random, optimization, output and material-table
//! cards and PARAMs build byte-identical files (every entry but `recipe.json`, which names the
//! source deck, and the manifest's line of it), with one note
//! per category; a SOL that is not a plain modal or response solution is refused by its line;
//! a file's format comes from its content.

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::common::{exe, scratch};

/// A solid block (two CHEXA), two CQUAD4 on its top face's edge and one on the top face (it
/// holds the others' rotation at the edge: without it they hinge there, a zero mode), a CBAR,
/// the block's end held by SPC1, EIGRL for six modes (SI units).
fn structural() -> String {
    let mut s = String::from(
        "SOL 103\nCEND\nTITLE = catalogue acceptance\nMETHOD = 1\nSPC = 1\nDISPLACEMENT = ALL\n\
         BEGIN BULK\nEIGRL,1,,,6\nMAT1,1,2.1e11,,0.3,7850.\nPSOLID,1,1\n\
         PSHELL,2,1,0.005,1,,1\nPBAR,3,1,1.e-4,1.e-9,1.e-9,2.e-9\n",
    );
    for iz in 0..2 {
        for iy in 0..2 {
            for ix in 0..3 {
                let id = 1 + ix + 3 * iy + 6 * iz;
                s += &format!(
                    "GRID,{id},,{:?},{:?},{:?}\n",
                    0.1 * ix as f64,
                    0.1 * iy as f64,
                    0.1 * iz as f64
                );
            }
        }
    }
    s += "GRID,13,,0.3,0.,0.1\nGRID,14,,0.3,0.1,0.1\nGRID,15,,0.4,0.,0.1\n\
          GRID,16,,0.4,0.1,0.1\nGRID,17,,0.6,0.,0.1\n\
          CHEXA,1,1,1,2,5,4,7,8\n,11,10\nCHEXA,2,1,2,3,6,5,8,9\n,12,11\n\
          CQUAD4,3,2,9,13,14,12\nCQUAD4,4,2,13,15,16,14\nCQUAD4,6,2,8,9,12,11\n\
          CBAR,5,3,15,17,0.,0.,1.\n\
          SPC1,1,123,1,4,7,10\n";
    s
}

/// The appended blocks: every card the issue names, with valid fields.
const AEROELASTIC: &str = "\
AERO,0,250.,1.,1.225
AEROS,0,0,1.,10.,10.
PAERO1,1
CAERO1,1001,1,0,4,2,,,1
,0.,0.,0.,1.,0.,1.,0.,1.
SET1,100,13,14,15,16
SPLINE1,2001,1001,1001,1008,100
SPLINE2,2002,1001,1001,1008,100,0.,1.
AEFACT,10,0.,0.5,1.
FLFACT,1,1.
FLFACT,2,0.8
FLFACT,3,0.1,0.2,0.3
MKAERO1,0.8
,0.1,0.2,0.3
FLUTTER,30,PK,1,2,3,L,4
GUST,40,94,0.01,0.,250.
AECOMP,WING,CAERO,1001
MONPNT3,WROOT,wing root
,123456,100,,0,0.,0.,0.1
MONDSP1,TIPDISP,tip displacement
,3,WING,0,0.6,0.,0.1
MONPNT1,AEROLD,aerodynamic load
,123456,WING,0.3,0.,0.
TRIM,50,0.8,1000.,ANGLEA,0.1
AESTAT,501,ANGLEA
AELIST,600,1001,1002
AESURF,601,AIL,1,600
PARAM,MACH,0.8
PARAM,Q,1000.
PARAM,KINDEX,0.1
PARAM,GUSTAERO,-1
";

const DYNAMIC: &str = "\
FREQ1,60,1.,2.,100
DAREA,70,13,3,1.
TABLED1,80
,0.,1.,1000.,1.,ENDT
TABLED2,81,0.
,0.,1.,1000.,1.,ENDT
TABLED3,82,0.,1.
,0.,1.,1000.,1.,ENDT
TABLED4,83,0.,1.,0.,1000.
,1.,0.5,ENDT
RLOAD1,90,70,,,80
RLOAD2,91,70,,,80,81
TLOAD1,92,70,,0,82
TLOAD2,93,70,,0,0.,1.,10.,0.
DLOAD,94,1.,1.,90,1.,91
EPOINT,5001,5002
TF,95,5001,0,1.,0.,0.
,13,3,0.5,0.,0.
SPCD,96,13,3,0.001
TSTEP,97,100,0.001,1
PARAM,LMODES,10
PARAM,MODACC,0
PARAM,NOUE,2
PARAM,IFTM,0
";

const RANDOM: &str = "\
RANDPS,98,1,1,1.,0.,99
TABRND1,99
,1.,0.1,1000.,0.1,ENDT
";

const OPTIMIZATION: &str = "\
DESVAR,1,THICK,0.005,0.001,0.01
DEQATN,10,F(T)=T/12.
DVPREL1,1,PSHELL,2,T
,1,1.
DVPREL2,2,PBAR,3,A,,,10
,DESVAR,1
DRESP1,1,W,WEIGHT
DRESP2,2,FRQ,10
,DESVAR,1
DCONSTR,1,1,,0.5
DOPTPRM,DESMAX,10
DSCREEN,FREQ,-0.5,20
";

const OUTPUT: &str = "\
PLOTEL,9001,1,17
PARAM,POST,-1
PARAM,PRGPST,NO
PARAM,DDRMM,-1
PARAM,OIBULK,YES
PARAM,MPTUNIT,0
";

const MATERIAL_TABLE: &str = "\
TABLEM1,300
,20.,2.1e11,200.,1.9e11,ENDT
";

/// The notes' categories the appended blocks make, one note each.
const CATEGORIES: [&str; 6] = [
    "aeroelastic",
    "dynamic loads and tables",
    "random response",
    "optimization",
    "output and plotting",
    "material tables",
];

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// `flexbody build DECK --method normal --units si --json -o OUT` (the deck has no interface): (the JSON report, stderr, success).
fn build(deck: &Path, out: &Path) -> (serde_json::Value, String, bool) {
    let o = exe()
        .arg("build")
        .arg(deck)
        .args(["--method", "normal", "--units", "si", "--json", "-o"])
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let report = serde_json::from_slice(&o.stdout).unwrap_or(serde_json::Value::Null);
    (report, stderr, o.status.success())
}

/// Every entry of a zip archive: name → bytes.
fn entries(path: &Path) -> Vec<(String, Vec<u8>)> {
    let mut z = zip::ZipArchive::new(std::fs::File::open(path).unwrap()).unwrap();
    (0..z.len())
        .map(|k| {
            let mut e = z.by_index(k).unwrap();
            let mut bytes = Vec::new();
            e.read_to_end(&mut bytes).unwrap();
            (e.name().expect("UTF-8 name").to_string(), bytes)
        })
        .collect()
}

/// A manifest (JSON) with every object named `recipe.json` removed.
fn without_recipe(manifest: &[u8]) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Array(items) => {
                items.retain(|i| i["name"] != "recipe.json");
                items.iter_mut().for_each(strip);
            }
            serde_json::Value::Object(map) => map.values_mut().for_each(strip),
            _ => {}
        }
    }
    let mut v: serde_json::Value = serde_json::from_slice(manifest).expect("manifest is JSON");
    let before = v.to_string().len();
    strip(&mut v);
    assert!(
        v.to_string().len() < before,
        "no recipe.json in the manifest"
    );
    v
}

#[test]
fn appended_non_structural_blocks_change_no_byte_and_make_one_note_per_category() {
    let dir = scratch("catalogue_acceptance");
    let plain = structural();
    let full = format!(
        "{plain}{AEROELASTIC}{DYNAMIC}{RANDOM}{OPTIMIZATION}{OUTPUT}{MATERIAL_TABLE}ENDDATA\n"
    );
    let a = write(&dir, "structure.bdf", &format!("{plain}ENDDATA\n"));
    let b = write(&dir, "structure_and_more.bdf", &full);
    let (out_a, out_b) = (dir.join("a.flexbody"), dir.join("b.flexbody"));
    let (_, err_a, ok_a) = build(&a, &out_a);
    assert!(ok_a, "{err_a}");
    let (report, err_b, ok_b) = build(&b, &out_b);
    assert!(ok_b, "{err_b}");
    let (ea, eb) = (entries(&out_a), entries(&out_b));
    let names = |e: &[(String, Vec<u8>)]| e.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&ea), names(&eb));
    let mut compared = 0;
    for ((name, x), (_, y)) in ea.iter().zip(&eb) {
        match name.as_str() {
            // the recipe names the source deck (its name, size, hash): it differs
            "recipe.json" => {}
            // the manifest lists the recipe's size and hash: equal but for that entry
            "manifest.json" => {
                assert_eq!(without_recipe(x), without_recipe(y), "manifest differs");
                compared += 1;
            }
            _ => {
                assert!(x == y, "entry {name} differs");
                compared += 1;
            }
        }
    }
    assert!(compared >= 5, "{:?}", names(&ea));
    let notes: Vec<&str> = (report["deck"].as_array())
        .unwrap_or_else(|| panic!("no deck notes in {report}"))
        .iter()
        .filter_map(|n| n.as_str())
        .collect();
    for category in CATEGORIES {
        let head = format!("{category} cards not read (");
        let n = notes.iter().filter(|l| l.starts_with(&head)).count();
        assert_eq!(n, 1, "{category}: {notes:#?}");
    }
    // every card of the blocks is named in a note, with its line
    let all = notes.join("\n");
    for block in [
        AEROELASTIC,
        DYNAMIC,
        RANDOM,
        OPTIMIZATION,
        OUTPUT,
        MATERIAL_TABLE,
    ] {
        for line in block.lines().filter(|l| !l.starts_with(',')) {
            let mut f = line.split(',');
            let card = f.next().unwrap();
            let key = match card {
                "PARAM" => format!("PARAM:{}", f.next().unwrap()),
                c => c.to_owned(),
            };
            let at = full.lines().position(|l| l == line).unwrap() + 1;
            assert!(
                all.contains(&format!(" {key} (")) && all.contains(&format!("{at}")),
                "{key} (line {at}) in no note: {all}"
            );
        }
    }
}

#[test]
fn an_unknown_card_is_still_refused_by_line() {
    let dir = scratch("catalogue_unknown");
    let deck = format!("{}CFOOBAR,1,2,3\nENDDATA\n", structural());
    let at = deck.lines().position(|l| l.starts_with("CFOOBAR")).unwrap() + 1;
    let p = write(&dir, "unknown.bdf", &deck);
    let (_, err, ok) = build(&p, &dir.join("u.flexbody"));
    assert!(!ok);
    assert!(
        err.contains(&format!("unknown.bdf:{at}: CFOOBAR 1: not read")),
        "{err}"
    );
}

/// A SOL that is not a normal-modes or linear response solution is refused by its line,
/// never read as plain modes: buckling, nonlinear, NASTRAN-95's rigid format 13 (normal modes
/// with differential stiffness), SOL 400 modes after a preload, optimization.
#[test]
fn solutions_other_than_modes_or_linear_response_are_refused_by_line() {
    let dir = scratch("catalogue_sol");
    for (sol, says) in [
        ("105", "buckling"),
        ("106", "nonlinear"),
        ("400", "nonlinear"),
        ("13", "rigid format 13"),
        ("200", "design optimization"),
        ("SEBUCKL", "buckling"),
    ] {
        let deck = structural().replacen("SOL 103", &format!("SOL {sol}"), 1) + "ENDDATA\n";
        let p = write(&dir, &format!("sol{sol}.bdf"), &deck);
        let (_, err, ok) = build(&p, &dir.join("s.flexbody"));
        assert!(!ok, "SOL {sol} built");
        assert!(
            err.contains(&format!("sol{sol}.bdf:1: SOL {sol} (executive control): "))
                && err.contains(says)
                && err.contains("--ignore SOL"),
            "SOL {sol}: {err}"
        );
    }
    // a linear response solution builds the structure's normal modes, with a note
    let deck = structural().replacen("SOL 103", "SOL 111", 1) + "ENDDATA\n";
    let p = write(&dir, "sol111.bdf", &deck);
    let (report, err, ok) = build(&p, &dir.join("r.flexbody"));
    assert!(ok, "{err}");
    assert!(report["deck"]
        .to_string()
        .contains("SOL 111 (modal frequency response"));
    // NASTRAN-95's SOL 13 dropped on purpose: the unloaded modes, with a warning
    let p = dir.join("sol13.bdf");
    let o = exe()
        .arg("build")
        .arg(&p)
        .args([
            "--method", "normal", "--units", "si", "--ignore", "SOL", "-o",
        ])
        .arg(dir.join("i.flexbody"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && err.contains("1 SOL ("), "{err}");
}

#[test]
fn format_comes_from_the_content() {
    let dir = scratch("catalogue_format");
    let deck = structural() + "ENDDATA\n";
    // a Nastran deck named .dat or with no known extension is read as Nastran
    for name in ["deck.dat", "deck.txt"] {
        let p = write(&dir, name, &deck);
        let (_, err, ok) = build(&p, &dir.join("d.flexbody"));
        assert!(ok, "{name}: {err}");
    }
    // named .inp: the extension says Abaqus, the content Nastran: an error naming --format
    let p = write(&dir, "deck.inp", &deck);
    let (_, err, ok) = build(&p, &dir.join("d.flexbody"));
    assert!(!ok);
    assert!(
        err.contains(
            "deck.inp: the extension says Abaqus/CalculiX but the content looks like Nastran"
        ) && err.contains("--format bdf"),
        "{err}"
    );
    // and read as Nastran with --format bdf
    let o = exe()
        .arg("build")
        .arg(&p)
        .args([
            "--format", "bdf", "--method", "normal", "--units", "si", "-q", "-o",
        ])
        .arg(dir.join("f.flexbody"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // an Abaqus deck named .bdf
    let inp = "*HEADING\nblock\n*NODE\n1, 0., 0., 0.\n*ELEMENT, TYPE=C3D4, ELSET=E\n";
    let p = write(&dir, "abaqus.bdf", inp);
    let (_, err, _) = build(&p, &dir.join("x.flexbody"));
    assert!(
        err.contains("the extension says Nastran but the content looks like Abaqus/CalculiX")
            && err.contains("--format inp"),
        "{err}"
    );
    // issue 47 item 8: a README saved as .inp is no deck
    let p = write(
        &dir,
        "readme.inp",
        "# Model\n\nRun it with any solver.\nSee NOTES.\n",
    );
    let (_, err, ok) = build(&p, &dir.join("r.flexbody"));
    assert!(!ok);
    assert!(
        err.contains("readme.inp: not a model file: it does not look like an Abaqus/CalculiX deck")
            && !err.contains("--ignore"),
        "{err}"
    );
    // a flexbody file given to build
    let (_, e, ok) = build(&write(&dir, "ok.bdf", &deck), &dir.join("ok.flexbody"));
    assert!(ok, "{e}");
    let (_, err, ok) = build(&dir.join("ok.flexbody"), &dir.join("again.flexbody"));
    assert!(!ok);
    assert!(
        err.contains("ok.flexbody: not a model file")
            && err.contains("flexbody inspect")
            && err.contains("--format"),
        "{err}"
    );
}
