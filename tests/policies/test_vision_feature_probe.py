"""analysis/policies/vision_feature_probe.py: the per-token probe reads a count that the tokens hold
and does not read one they do not."""

import torch
from helpers.analysis_scripts import load


def test_the_probe_reads_a_count_the_tokens_hold_and_not_one_they_do_not():
    probe = load("analysis/policies/vision_feature_probe.py").probe
    g = torch.Generator().manual_seed(0)
    tokens = torch.randn(3000, 12, 16, generator=g)
    held = torch.zeros(3000, 12, 16)
    marked = torch.rand(3000, 12, generator=g) < 0.12  # tokens that show an object
    held[..., 0] = marked.float() * 3.0
    held = held + 0.3 * tokens
    labels = marked.sum(1).clamp(max=3)
    train = torch.arange(3000) < 2400
    test = ~train
    readable = (probe(held, labels, train)[test] == labels[test]).float().mean().item()
    noise = torch.randn(3000, 12, 16, generator=g)
    unreadable = (probe(noise, labels, train)[test] == labels[test]).float().mean().item()
    majority = (labels[test] == torch.bincount(labels[train]).argmax()).float().mean().item()
    assert readable > 0.9
    assert unreadable < majority + 0.05
