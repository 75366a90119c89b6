"""The benchmark's tasks, one module per row of the paper's inventory table (discovered automatically)."""
