"""Online per-frame annotations (paper App. "Per-Frame Data and Online Annotations")."""
