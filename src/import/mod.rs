//! FE model importers: Abaqus/CalculiX `.inp`, Nastran `.bdf`, Gmsh `.msh`, Matrix Market.
