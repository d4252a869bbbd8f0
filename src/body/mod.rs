//! The body stage: from a mode set and its model to what the file carries besides the modes —
//! graphics faces ([`faces`]), the inertia invariants (lumped [`invariants`], consistent
//! [`invariants_consistent`]), modal stress/strain shapes of solids ([`stress`]) and shells'
//! fibres ([`shell_stress`]), and modal damping ([`damping`]).
pub mod damping;
pub mod faces;
pub mod invariants;
pub mod invariants_consistent;
pub mod shell_stress;
pub mod stress;
