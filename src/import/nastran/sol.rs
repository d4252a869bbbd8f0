//! The executive control's `SOL`: a normal-modes solution is what the body is built from; a
//! linear response solution (statics, frequency or transient response, complex modes,
//! aeroelastic) builds the same structure's normal modes, with a note; every other solution —
//! buckling, nonlinear (SOL 106/129/400, modes after a nonlinear preload), NASTRAN-95's rigid
//! format 13 (normal modes with differential stiffness), heat transfer, cyclic symmetry,
//! design optimization — is refused by its line, never read as plain modes. NASTRAN-95's
//! rigid formats (`SOL 1` … `SOL 16`, after `APP DISP`) have the numbers MSC's early
//! solutions kept.

/// What the build does with a deck's solution.
pub(super) enum Disposition {
    /// Normal modes: the body.
    Modes,
    /// A linear response solution: the body is the structure's normal modes (the name of
    /// the solution, for the note).
    Response(&'static str),
    /// Refused, with the reason.
    Refused(&'static str),
}

/// Reason of the refusal of a nonlinear solution.
const NONLINEAR: &str = "a nonlinear solution (or normal modes after a nonlinear static \
                         preload): flexbody's preload is linear; write the preload as SOL 103 \
                         with STATSUB(PRELOAD) and a static subcase";

/// The disposition of `SOL value` (upper case; a number or a structured solution name).
pub(super) fn disposition(value: &str) -> Disposition {
    use Disposition::{Modes, Refused, Response};
    let word = value.split([' ', ',']).next().unwrap_or("");
    match word {
        "103" | "3" | "SEMODES" | "MODES" => Modes,
        "101" | "1" | "SESTATIC" | "STATICS" => Response("linear statics"),
        "2" => Response("linear statics with inertia relief (NASTRAN-95 rigid format 2)"),
        "108" | "8" | "SEDFREQ" => Response("direct frequency response"),
        "111" | "11" | "SEMFREQ" => Response("modal frequency response"),
        "109" | "9" | "SEDTRAN" => Response("direct transient response"),
        "112" | "12" | "SEMTRAN" => Response("modal transient response"),
        "107" | "7" | "SEDCEIG" => Response("direct complex eigenvalues"),
        "110" | "10" | "SEMCEIG" => Response("modal complex eigenvalues"),
        "144" | "AESTAT" => Response("static aeroelastic response"),
        "145" | "SEFLUTTR" => Response("flutter"),
        "146" | "SEAERO" => Response("dynamic aeroelastic response"),
        "105" | "5" | "SEBUCKL" => Refused(
            "buckling (SOL 105): its modes are buckling modes of a preloaded structure, not the \
             body's vibration modes; build the normal modes from SOL 103 (with STATSUB(PRELOAD) \
             for a preload)",
        ),
        "13" => Refused(
            "NASTRAN-95 rigid format 13, normal modes with differential stiffness: modes after a \
             static preload in a form this importer does not read; write it as SOL 103 with \
             STATSUB(PRELOAD) naming the static subcase",
        ),
        "4" => Refused(
            "NASTRAN-95 rigid format 4, static analysis with differential stiffness: not \
             modelled; for modes after a preload write SOL 103 with STATSUB(PRELOAD)",
        ),
        "106" | "NLSTATIC" | "129" | "NLTRAN" | "400" | "401" | "402" | "NONLIN" | "600"
        | "700" | "6" => Refused(NONLINEAR),
        "153" | "159" | "16" | "NLSCSH" | "NLTCSH" => Refused(
            "heat transfer: no stiffness or mass (build the body from a SOL 103 deck of the \
             structure)",
        ),
        "114" | "115" | "116" | "118" | "14" | "15" => {
            Refused("cyclic symmetry: the deck is one sector of the body, not modelled")
        }
        "200" | "DESOPT" => Refused(
            "design optimization (SOL 200): the analysis model is the design at its variables' \
             values, which DVPREL/DVMREL/DVGRID may take from other cards than the ones \
             written; build from a SOL 103 deck of the design",
        ),
        _ => Refused("a solution sequence this importer does not know"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solutions_are_modes_responses_or_refused() {
        assert!(matches!(disposition("103"), Disposition::Modes));
        assert!(matches!(disposition("SEMODES"), Disposition::Modes));
        assert!(matches!(disposition("111"), Disposition::Response(_)));
        for refused in ["105", "106", "400", "13", "200", "153", "DMAPX"] {
            assert!(
                matches!(disposition(refused), Disposition::Refused(_)),
                "{refused}"
            );
        }
    }
}
