"""The validity suite: adversaries that must not score (``adversaries``) run over every task, with
records, targets and the table (``suite``); ``activearena-validity`` is its CLI."""
