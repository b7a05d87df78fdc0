"""Verification report for pdmpm: load results, plot, render one self-contained HTML page."""
