//! CalculiX's shells as ccx 2.20 computes them (issue 34): ccx has no shell element; it
//! expands every S3, S4R, S6, S8, S8R into one layer of C3D6, C3D8R, C3D15, C3D20, C3D20R
//! bricks and joins the shell's nodes to the bricks by linear equations (CalculiX 2.20 manual
//! §6.2.x "Shell elements"; the source's gen3delem, gen3dnor, gen3dfrom2d, gen3dconnect,
//! gen3dboun, gen3dforc). This module does the same to the model the reader made:
//!
//! * **Normals** (gen3dnor): at every shell node, the normal of each of its shell elements is
//!   ∂x/∂ξ × ∂x/∂η of the element's own interpolation at the node; the normals of the elements
//!   within 20° (cos > 0.939693) of the one of the element with the smallest id, of the same
//!   thickness there, are averaged (sum of unit normals, normalized). A node where some
//!   element falls outside that group (a fold, or a jump of thickness) is where ccx forms a
//!   rigid "knot": refused, naming the node.
//! * **Nodes** (gen3dfrom2d): each shell node x gets a bottom node x − (1/2 + o)·t·n and a top
//!   node x + (1/2 − o)·t·n; a node that is a corner of a quadratic element also a middle node
//!   x − o·t·n (ccx's C3D20 nodes 17–20, C3D15 nodes 13–15), o the section's `OFFSET=` (in
//!   thicknesses: the shell's nodes lie o·t above its mid-surface; elements of another OFFSET
//!   meeting at a node are ccx's knot: refused). ccx's thickness: the section's, or `*NODAL
//!   THICKNESS` where the section asks for it (`thickness.rs`). The equations below do not
//!   see the offset (as ccx's): a shell node moves as the mean of its bottom and top nodes.
//! * **Elements**: S8 → C3D20, S8R → C3D20R, S6 → C3D15, S4R → C3D8R, S3 → C3D6, S4 → C3D8I
//!   (`ModelParams::solid_bubbles`, ccx 2.20's incompatible-mode brick with its modes' mass:
//!   `fe::elements::solid_incompatible`; refused beside plain C3D8/C3D6 and S3, whose linear
//!   wedges would take the modes too), with the shell's material (ccx's integration:
//!   `ModelParams::ccx_solid_rules`, `fe::elements`); bottom face first, in the shell's node
//!   order.
//! * **Equations** (`shell_equations.rs`) joining a shell node n (which stays in the model:
//!   sets, loads and interfaces name it) to its bottom b, middle m and top t nodes, per
//!   direction d, the first rule that applies making u_b,d the dependent dof:
//!   1. n belongs to a solid element, a spring or a mass (gen3dconnect), or to an equation or
//!      rigid element (gen3dmpc): u_b + u_t − 2 u_n = 0;
//!   2. a `*BOUNDARY` holds direction d of n (gen3dboun): u_b + u_t − 2 u_n = 0, and for a
//!      middle node u_m − u_n = 0 (n keeps its constraint);
//!   3. otherwise as a force on n would join it (gen3dforc): u_b + u_t − 2 u_n = 0, or at a
//!      corner of a quadratic element −u_b + 4 u_m − u_t − 2 u_n = 0 (the quadratic
//!      interpolation through the thickness). ccx writes these only for loaded directions; for
//!      a free node they change no frequency (u_n, without stiffness or mass of its own, only
//!      replaces u_b as the unknown), and they give every shell node the meaning of ccx's
//!      loaded node.
//! * **Rotations held** by a `*BOUNDARY` (dofs 4–6 of n, gen3dboun's mean-rotation equations,
//!   linearized as in a linear step): a rotation about the normal (|a·n| > 0.999) is dropped;
//!   the first other axis a₁, projected on the tangent plane, gives e₁; any further axis not
//!   along e₁ adds e₂ = n × e₁. Each held tangent axis e gives (e × n)·(u_t − u_b) = h θ_k,
//!   the linearized mean rotation of the bottom and top nodes (h apart) about e equal to the
//!   held rotation k of n that made the axis: n's held rotation stands for ccx's "angle node"
//!   (its SPC holds the angle), so n keeps its `*BOUNDARY` as the deck gives it.
//! * **Pressures** `P` on a shell (gen3delem's loads: ccx's `P1`) act on the bricks' bottom faces,
//!   along +n for p > 0.
//!
//! * **Faces** `SNEG`/`SPOS` (`S1`/`S2`) of a shell in a `*TIE` or `*COUPLING` surface are the
//!   brick's bottom and top faces (`faces.rs`): the expansion then runs before the ties
//!   ([`expand_elements`] from `resolve::finish`, the loads after them: [`expand_loads`]), and a
//!   free shell node's rule-3 equation is written with the shell node dependent, so that its
//!   bottom node stays free for a tie as in ccx (which writes no equation for it).
//! * `*EQUATION` terms on rotations of shell nodes: ccx 2.20 applies them to rotational dofs of
//!   the expanded nodes, which no brick has: an equation of such terms only is left out with a
//!   warning (`connectors.rs`), one mixing them with other dofs is refused.
//!
//! What ccx would do with a rigid knot (folds, beams meeting shells, rotations of nodes in
//! rigid elements, moments and rotary inertia on shell nodes, rotations held in a
//! rotated frame), and composite or non-isotropic shell sections, are refused naming the node
//! or element and its line.

use std::collections::{BTreeMap, HashMap};

use super::shell_nodes::{parse_err, unit, Expanded, Xyz};
pub use super::shell_nodes::{Place, ShellElements};
use crate::import::ImportError;
use crate::model::geometry::{cross, dot};
use crate::model::{Elasticity, Element, ElementKind, Model, Node, NodeIndex, Property, Section};

/// The element types this module expands.
pub const SHELL_TYPES: &[&str] = &["S3", "S4", "S4R", "S6", "S8", "S8R"];

/// cos 20°: ccx's limit for one mean normal (gen3dnor).
const SAME_NORMAL: f64 = 0.939693;
/// The shell's brick and whether a corner node of it has a middle node.
fn brick_of(card: &str) -> Option<(ElementKind, bool)> {
    Some(match card {
        "S8" => (ElementKind::Hex20, true),
        "S8R" => (ElementKind::Hex20R, true),
        "S6" => (ElementKind::Prism15, true),
        "S4R" => (ElementKind::Hex8R, false),
        // ccx's C3D8I: the model's linear hexahedra take the incompatible modes (`expand`)
        "S4" => (ElementKind::Hex8, false),
        "S3" => (ElementKind::Prism6, false),
        _ => return None,
    })
}

/// The ccx type of the brick a shell type is expanded into (`None`: not a shell type).
pub fn brick_card(card: &str) -> Option<&'static str> {
    Some(match card {
        "S8" => "C3D20",
        "S8R" => "C3D20R",
        "S6" => "C3D15",
        "S4R" => "C3D8R",
        "S4" => "C3D8I",
        "S3" => "C3D6",
        _ => return None,
    })
}

/// The number of corner nodes of the shell a brick is made of.
fn corners(brick: ElementKind) -> usize {
    match brick {
        ElementKind::Prism6 | ElementKind::Prism15 => 3,
        ElementKind::Hex8 | ElementKind::Hex8R | ElementKind::Hex20 | ElementKind::Hex20R => 4,
        // no shell is expanded into these
        ElementKind::Tet4
        | ElementKind::Tet10
        | ElementKind::Hex8Bbar
        | ElementKind::Pyram5
        | ElementKind::Pyram13
        | ElementKind::Pyram13Ansys
        | ElementKind::Beam2
        | ElementKind::Bar2
        | ElementKind::Beam2Linear
        | ElementKind::Beam3Quadratic
        | ElementKind::Beam4Cubic
        | ElementKind::Rod2
        | ElementKind::Beam3
        | ElementKind::Tri3
        | ElementKind::Quad4
        | ElementKind::Tri6
        | ElementKind::Quad8 => 0,
    }
}

/// ∂x/∂ξ × ∂x/∂η of a shell element at its local node `j` (ccx's norshell3/4/6/8: the
/// element's own isoparametric interpolation, Zienkiewicz & Taylor, *The Finite Element
/// Method* vol. 1, §8.5 serendipity and triangle shape functions).
pub(super) fn node_normal(kind: ElementKind, x: &[Xyz], j: usize) -> Xyz {
    // (dN/dξ, dN/dη) of every node at node j's local coordinates
    let d: Vec<(f64, f64)> = match kind {
        ElementKind::Tri3 => vec![(-1.0, -1.0), (1.0, 0.0), (0.0, 1.0)],
        ElementKind::Quad4 | ElementKind::Quad8 => {
            const AT: [(f64, f64); 8] = [
                (-1.0, -1.0),
                (1.0, -1.0),
                (1.0, 1.0),
                (-1.0, 1.0),
                (0.0, -1.0),
                (1.0, 0.0),
                (0.0, 1.0),
                (-1.0, 0.0),
            ];
            let (s, t) = AT[j];
            if kind == ElementKind::Quad4 {
                (AT[..4].iter())
                    .map(|&(si, ti)| (0.25 * si * (1.0 + t * ti), 0.25 * ti * (1.0 + s * si)))
                    .collect()
            } else {
                (AT.iter().enumerate())
                    .map(|(i, &(si, ti))| match i {
                        0..=3 => (
                            0.25 * si * (1.0 + t * ti) * (2.0 * s * si + t * ti),
                            0.25 * ti * (1.0 + s * si) * (s * si + 2.0 * t * ti),
                        ),
                        4 | 6 => (-s * (1.0 + t * ti), 0.5 * ti * (1.0 - s * s)),
                        _ => (0.5 * si * (1.0 - t * t), -t * (1.0 + s * si)),
                    })
                    .collect()
            }
        }
        // not a shell: no normal (the callers pass shells only)
        ElementKind::Tet4
        | ElementKind::Tet10
        | ElementKind::Hex8
        | ElementKind::Hex8R
        | ElementKind::Hex8Bbar
        | ElementKind::Hex20
        | ElementKind::Hex20R
        | ElementKind::Prism6
        | ElementKind::Prism15
        | ElementKind::Pyram5
        | ElementKind::Pyram13
        | ElementKind::Pyram13Ansys
        | ElementKind::Beam2
        | ElementKind::Bar2
        | ElementKind::Beam2Linear
        | ElementKind::Beam3Quadratic
        | ElementKind::Beam4Cubic
        | ElementKind::Rod2
        | ElementKind::Beam3 => return [0.0; 3],
        ElementKind::Tri6 => {
            const AT: [(f64, f64); 6] = [
                (0.0, 0.0),
                (1.0, 0.0),
                (0.0, 1.0),
                (0.5, 0.0),
                (0.5, 0.5),
                (0.0, 0.5),
            ];
            let (s, t) = AT[j];
            let l = 1.0 - s - t;
            vec![
                (1.0 - 4.0 * l, 1.0 - 4.0 * l),
                (4.0 * s - 1.0, 0.0),
                (0.0, 4.0 * t - 1.0),
                (4.0 * (l - s), -4.0 * s),
                (4.0 * t, 4.0 * s),
                (-4.0 * t, 4.0 * (l - t)),
            ]
        }
    };
    let mut gs = [0.0; 3];
    let mut gt = [0.0; 3];
    for (xi, (ds, dt)) in x.iter().zip(d) {
        for k in 0..3 {
            gs[k] += ds * xi[k];
            gt[k] += dt * xi[k];
        }
    }
    cross(gs, gt)
}

/// One shell element to expand: its index, place, brick and thickness at each node.
struct ShellElement<'a> {
    index: usize,
    place: &'a Place,
    brick: ElementKind,
    quadratic: bool,
    thickness: Vec<f64>,
    /// `*SHELL SECTION, OFFSET=` (in thicknesses; SPOS = 0.5, SNEG = −0.5).
    offset: f64,
}

/// The expanded nodes of every shell node, from [`expand_elements`] for [`expand_loads`].
pub struct Expansion {
    nodes: BTreeMap<NodeIndex, Expanded>,
}

impl Expansion {
    /// Whether node `n` is a shell node that was expanded.
    pub fn is_shell_node(&self, n: NodeIndex) -> bool {
        self.nodes.contains_key(&n)
    }

    /// The shell nodes that were expanded.
    pub fn shell_nodes(&self) -> impl Iterator<Item = NodeIndex> + '_ {
        self.nodes.keys().copied()
    }
}

/// Expand the deck's shells into bricks as ccx 2.20 does (module doc); `offsets`: the
/// `*SHELL SECTION, OFFSET` of each property (in thicknesses).
pub fn expand(
    model: &mut Model,
    shells: &ShellElements,
    offsets: &[f64],
) -> Result<(), ImportError> {
    let expansion = expand_elements(model, shells, offsets, false)?;
    expand_loads(model, &expansion, shells);
    Ok(())
}

/// The bricks, their nodes and the equations joining them to the shell nodes (module doc);
/// `free_node_dependent`: a free shell node's equation (rule 3) is written with the shell node
/// dependent, u_n = (u_b + u_t)/2 (or its quadratic form), so that its bottom node stays free
/// for a `*TIE` or `*COUPLING` on the brick's faces as in ccx (which writes no equation there).
pub fn expand_elements(
    model: &mut Model,
    shells: &ShellElements,
    offsets: &[f64],
    free_node_dependent: bool,
) -> Result<Expansion, ImportError> {
    let elements = shell_elements(model, shells, offsets)?;
    if elements.is_empty() {
        return Ok(Expansion {
            nodes: BTreeMap::new(),
        });
    }
    // the first shell element of each shell node: where its errors point
    let first_place: BTreeMap<NodeIndex, &Place> = (elements.iter().rev())
        .flat_map(|e| (model.elements[e.index].nodes.iter()).map(move |&n| (n, e.place)))
        .collect();
    let expanded = expand_nodes(model, &elements)?;
    replace_elements(model, &elements, &expanded);
    if elements.iter().any(|e| e.place.card == "S4") {
        // ccx 2.20's C3D8I (`fe::elements::solid_incompatible`); `shell_elements` refused S4
        // beside plain C3D8/C3D6
        model.params.solid_bubbles = true;
    }
    let rules = super::shell_equations::Joining::of(model, &expanded, &first_place)?;
    rules.write(model, &expanded, free_node_dependent);
    Ok(Expansion { nodes: expanded })
}

/// The loads on expanded shells: moments refused, pressures moved to the bricks' bottom faces,
/// temperatures given to the expanded nodes (module doc).
pub fn expand_loads(model: &mut Model, expansion: &Expansion, shells: &ShellElements) {
    let expanded = &expansion.nodes;
    if expanded.is_empty() {
        return;
    }
    refuse_moments(model, expanded);
    move_pressures(model, expanded, shells);
    if let Some(preload) = model.deck.preload.as_mut() {
        if let Some((dt, _)) = preload.thermal.as_mut() {
            // ccx gives the expanded nodes the shell node's temperature (gen3dtemp)
            let mut parent = vec![None; model.nodes.len()];
            for (&n, e) in expanded {
                for k in [Some(e.bottom), e.middle, Some(e.top)]
                    .into_iter()
                    .flatten()
                {
                    parent[k] = Some(n);
                }
            }
            let old = dt.len();
            let added: Vec<f64> = (parent[old..].iter())
                .map(|p| p.and_then(|n| dt.get(n).copied()).unwrap_or(0.0))
                .collect();
            dt.extend(added);
        }
    }
}

/// The shell elements with a section, checked: homogeneous isotropic sections, types ccx
/// expands into bricks flexbody forms as ccx does.
fn shell_elements<'a>(
    model: &Model,
    shells: &'a ShellElements,
    offsets: &[f64],
) -> Result<Vec<ShellElement<'a>>, ImportError> {
    let mut out = Vec::new();
    // S4 becomes ccx's C3D8I: the model's linear wedges would take incompatible modes too
    let bubbles = model.params.solid_bubbles
        || (model.elements.iter())
            .any(|e| e.property.is_some() && shells.get(&e.id).is_some_and(|p| p.card == "S4"));
    for (index, e) in model.elements.iter().enumerate() {
        let (Some(place), Some(p)) = (shells.get(&e.id), e.property) else {
            continue;
        };
        let entity = format!("*ELEMENT {} (TYPE={})", e.id, place.card);
        let prop = &model.properties[p];
        let Section::Shell(sh) = &prop.section else {
            continue;
        };
        let (brick, quadratic) = brick_of(place.card)
            .expect("`shells` holds SHELL_TYPES only, and brick_of maps each of them");
        if brick == ElementKind::Prism6 && bubbles {
            return Err(parse_err(
                place,
                entity,
                "S3 expanded into C3D6 beside C3D8I elements (or S4 shells, which ccx 2.20 \
                 expands into C3D8I) is not supported (the incompatible modes apply to every \
                 linear wedge of a model); --inp-shells native forms the shells as flexbody's \
                 shells"
                    .into(),
            ));
        }
        if place.card == "S4" && !model.params.solid_bubbles {
            if let Some(plain) = (model.elements.iter())
                .find(|o| matches!(o.kind, ElementKind::Hex8 | ElementKind::Prism6))
            {
                return Err(parse_err(
                    place,
                    entity,
                    format!(
                        "ccx 2.20 expands S4 into its C3D8I bricks, and C3D8I beside plain \
                         C3D8/C3D6 elements (element {}) is not supported: the incompatible \
                         modes apply to every linear hexahedron and wedge of a model; \
                         --inp-shells native forms S4 as flexbody's MITC4 shell",
                        plain.id
                    ),
                ));
            }
        }
        let m = prop.material;
        let homogeneous = sh.membrane
            && sh.bending == Some((m, 1.0))
            && sh.shear == Some((m, 5.0 / 6.0))
            && sh.nsm == 0.0;
        let isotropic = matches!(model.materials[m].elasticity, Elasticity::Isotropic)
            && !model.property_axes.contains_key(&p);
        if !homogeneous || !isotropic {
            return Err(parse_err(
                place,
                entity,
                format!(
                    "the shell section of ELSET={} is not one isotropic material without \
                     orientation, which is all ccx's expansion into bricks is done for here \
                     (ccx expands composite and oriented shells layer by layer)",
                    prop.name
                ),
            ));
        }
        let thickness = match model.shell_thickness.get(&index) {
            Some(t) => t.clone(),
            None => vec![sh.thickness; e.nodes.len()],
        };
        out.push(ShellElement {
            index,
            place,
            brick,
            quadratic,
            thickness,
            offset: offsets.get(p).copied().unwrap_or(0.0),
        });
    }
    Ok(out)
}

/// The mean normal at every shell node and its new bottom, middle and top nodes (gen3dnor,
/// gen3dfrom2d).
fn expand_nodes(
    model: &mut Model,
    elements: &[ShellElement],
) -> Result<BTreeMap<NodeIndex, Expanded>, ImportError> {
    // node → (element, local node)
    let mut at: BTreeMap<NodeIndex, Vec<(usize, usize)>> = BTreeMap::new();
    for (k, e) in elements.iter().enumerate() {
        for (j, &n) in model.elements[e.index].nodes.iter().enumerate() {
            at.entry(n).or_default().push((k, j));
        }
    }
    let mut next_id = model.max_node_id() + 1;
    let mut out = BTreeMap::new();
    for (&n, list) in &at {
        let normals: Vec<(u64, Xyz, f64, &Place)> = (list.iter())
            .map(|&(k, j)| {
                let e = &model.elements[elements[k].index];
                let x: Vec<Xyz> = e.nodes.iter().map(|&i| model.nodes[i].x).collect();
                let v = node_normal(e.kind, &x, j);
                (unit(v), e.id, elements[k].thickness[j], elements[k].place)
            })
            .map(|(v, id, t, place)| {
                v.map(|v| (id, v, t, place)).ok_or_else(|| {
                    let entity = format!("*ELEMENT {id} (TYPE={})", place.card);
                    parse_err(
                        place,
                        entity,
                        format!(
                            "the element's normal at node {} is zero (a degenerate element)",
                            model.nodes[n].id
                        ),
                    )
                })
            })
            .collect::<Result<_, _>>()?;
        // ccx's reference: the element with the smallest number
        let &(rid, rn, rt, rplace) = (normals.iter())
            .min_by_key(|x| x.0)
            .expect("a shell node belongs to at least one element (it was listed by one)");
        let offset_of = |id: u64| {
            (list.iter())
                .map(|&(k, _)| &elements[k])
                .find(|e| model.elements[e.index].id == id)
                .map_or(0.0, |e| e.offset)
        };
        let ro = offset_of(rid);
        if let Some(&(id, ..)) = normals.iter().find(|x| offset_of(x.0) != ro) {
            return Err(parse_err(
                rplace,
                format!("node {}", model.nodes[n].id),
                format!(
                    "shell elements {rid} and {id} meet there with another OFFSET ({ro} and \
                     {}): ccx joins them with a rigid knot, which flexbody does not form",
                    offset_of(id)
                ),
            ));
        }
        let mut sum = [0.0; 3];
        for &(id, v, t, _) in &normals {
            if dot(v, rn) <= SAME_NORMAL || (t - rt).abs() >= 1e-10 {
                return Err(parse_err(
                    rplace,
                    format!("node {}", model.nodes[n].id),
                    format!(
                        "shell elements {rid} and {id} meet there at more than 20° or with \
                         another thickness ({rt} and {t}): ccx joins them with a rigid knot, \
                         which flexbody does not form"
                    ),
                ));
            }
            sum = [sum[0] + v[0], sum[1] + v[1], sum[2] + v[2]];
        }
        let normal = unit(sum).expect("a sum of unit vectors within 20° of one is not zero");
        let corner_of_quadratic =
            (list.iter()).any(|&(k, j)| elements[k].quadratic && j < corners(elements[k].brick));
        let x = model.nodes[n].x;
        let frame = model.nodes[n].displacement_frame;
        let mut add = |s: f64| {
            model.nodes.push(Node {
                id: next_id,
                x: [
                    x[0] + s * rt * normal[0],
                    x[1] + s * rt * normal[1],
                    x[2] + s * rt * normal[2],
                ],
                displacement_frame: frame,
            });
            next_id += 1;
            model.nodes.len() - 1
        };
        // gen3dfrom2d: the reference surface OFFSET·t above the mid-surface
        let bottom = add(-0.5 - ro);
        let middle = corner_of_quadratic.then(|| add(-ro));
        let top = add(0.5 - ro);
        out.insert(
            n,
            Expanded {
                bottom,
                middle,
                top,
                normal,
            },
        );
    }
    Ok(out)
}

/// Each shell element becomes its brick with a solid section of the shell's material.
fn replace_elements(
    model: &mut Model,
    elements: &[ShellElement],
    expanded: &BTreeMap<NodeIndex, Expanded>,
) {
    let mut solid_of: HashMap<usize, usize> = HashMap::new();
    let mut next_property = model.properties.iter().map(|p| p.id).max().unwrap_or(0) + 1;
    for e in elements {
        let old = &model.elements[e.index];
        let p = old
            .property
            .expect("shell_elements keeps elements with a property only");
        let solid = *solid_of.entry(p).or_insert_with(|| {
            let shell = &model.properties[p];
            model.properties.push(Property {
                id: next_property,
                name: shell.name.clone(),
                material: shell.material,
                section: Section::Solid,
            });
            next_property += 1;
            model.properties.len() - 1
        });
        let corners = corners(e.brick);
        let nodes = &model.elements[e.index].nodes;
        let x = |n: &NodeIndex| expanded[n];
        let mut brick: Vec<NodeIndex> = Vec::with_capacity(e.brick.node_count());
        brick.extend(nodes[..corners].iter().map(|n| x(n).bottom));
        brick.extend(nodes[..corners].iter().map(|n| x(n).top));
        if e.quadratic {
            brick.extend(nodes[corners..].iter().map(|n| x(n).bottom));
            brick.extend(nodes[corners..].iter().map(|n| x(n).top));
            brick.extend((nodes[..corners].iter()).map(|n| {
                x(n).middle
                    .expect("a corner of a quadratic shell has a middle node (expand_nodes)")
            }));
        }
        let id = old.id;
        model.elements[e.index] = Element {
            id,
            kind: e.brick,
            nodes: brick,
            property: Some(solid),
            orientation: None,
        };
        model.shell_thickness.remove(&e.index);
    }
}

/// A pressure `P` on a shell acts, as ccx applies it, on the brick's bottom face (ccx's `P1`),
/// pushing into the brick: along +n. The reader made it a traction +p on the shell's face (along
/// the normal, as flexbody's own shells take it); here it moves to the bottom nodes, in the
/// shell's order (whose right-hand normal is n), with the same traction. Measured: a positive `P`
/// on an S4R plate moves it along +n in ccx 2.20.
fn move_pressures(
    model: &mut Model,
    expanded: &BTreeMap<NodeIndex, Expanded>,
    shells: &ShellElements,
) {
    for load in &mut model.loads {
        for part in &mut load.parts {
            if let crate::model::LoadPart::Surface { nodes, element, .. } = part {
                let all = nodes.iter().all(|n| expanded.contains_key(n));
                if shells.contains_key(element) && all {
                    for n in nodes.iter_mut() {
                        *n = expanded[n].bottom;
                    }
                }
            }
        }
    }
}

/// A moment on a shell node cannot be applied (the node has translations only): its load is
/// kept by name with the reason.
fn refuse_moments(model: &mut Model, expanded: &BTreeMap<NodeIndex, Expanded>) {
    for load in &mut model.loads {
        let moment = load.parts.iter().find_map(|p| match p {
            crate::model::LoadPart::Nodal { node, values }
                if expanded.contains_key(node) && values[3..].iter().any(|v| *v != 0.0) =>
            {
                Some(*node)
            }
            _ => None,
        });
        if let (Some(n), None) = (moment, &load.problem) {
            load.problem = Some(format!(
                "a moment on shell node {}: expanded into bricks as ccx does, a shell node has \
                 translations only (ccx's mean-rotation equations for moments are not formed)",
                model.nodes[n].id
            ));
        }
    }
}
