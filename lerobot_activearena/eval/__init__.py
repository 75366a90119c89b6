"""Leaderboard report from lerobot-eval runs: tables, failure decomposition, plots."""
