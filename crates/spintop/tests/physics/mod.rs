//! The paper's physics, one module per claim: the balance laws of Section 2, the central field, the closed forms of Section 4, the Euler angles (3.5), the full ALE (3.4), the shell of the appendix, the symmetric top and the paper's figures.

mod auto_model;
mod balance_laws;
mod central_field;
mod claims;
mod closed_forms;
mod errors_sweep;
mod euler_angles;
mod figures;
mod free_top;
mod full_ale;
mod general_full;
mod general_reduced;
mod invariance;
mod printed_errors;
mod shell_model;
mod symmetric_top;
