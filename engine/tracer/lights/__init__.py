"""Lights: one file per kind (its row and its per-path functions), a table, and one dispatch."""
