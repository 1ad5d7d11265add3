"""What the parity runs found, in words: read by report.py into docs/parity.md (per scene, and
"general" for the findings section). Measured numbers live in the generated table, not here."""

FINDINGS: dict[str, str] = {}
