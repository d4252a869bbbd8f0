//! FE model importers: Abaqus/CalculiX `.inp`, Nastran `.bdf`, Gmsh `.msh`, Matrix Market.
pub mod ccx_matrices;
