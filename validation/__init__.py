"""Validation harness: exact solutions, BEM/FEM comparisons, reports and VTK output."""
