//! Every CLI option parser (src/pipeline/options.rs, --damping, --interface against a small model):
//! `data[0]` picks the parser, the rest is the option's text (lines = repeated values).
#![no_main]
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

use flexbody::interface::{resolve_interfaces, SpiderKind};
use flexbody::model::Model;
use flexbody::options::*;

const MODEL: &[u8] = include_bytes!("../seeds/model/hex_pair.inp");

fn model() -> &'static Model {
    static M: OnceLock<Model> = OnceLock::new();
    M.get_or_init(|| {
        let path = flexbody_fuzz::scratch_file("model.inp", MODEL);
        flexbody::import::abaqus::read(&path).expect("the options target's model")
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&sel, rest)) = data.split_first() else {
        return;
    };
    let s = String::from_utf8_lossy(rest);
    let items: Vec<String> = s.lines().map(str::to_owned).collect();
    match sel % 14 {
        0 => drop(parse_units(&s)),
        1 => drop(parse_material(&s)),
        2 => drop(parse_reference_conditions(&items)),
        3 => drop(parse_reference_entries(&items)),
        4 => drop(parse_method(&s)),
        5 => drop(parse_mass(&s)),
        6 => drop(parse_beam_mass(&s)),
        7 => drop(parse_spider(&s)),
        8 => drop(parse_keep_nodes(&s)),
        9 => drop(parse_field_request(Some(&s))),
        10 => drop(parse_invariants(&s)),
        11 => drop(flexbody::damping::parse_damping(&s)),
        _ => {
            let spider =
                [SpiderKind::Rbe2, SpiderKind::Rbe3, SpiderKind::None][usize::from(sel % 3)];
            let mut m = model().clone();
            drop(resolve_interfaces(&mut m, &items, spider));
        }
    }
});
