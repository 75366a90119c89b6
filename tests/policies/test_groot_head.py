"""The GR00T run's flow-matching DiT head on tiny sizes (and its real size counted on the meta
device): shapes, the time distribution, masking of the backbone's padding, the Euler sampler's
direction, a loss that falls on a fixed batch, sampling that a seed fixes."""

import pytest
import torch

from lerobot_activearena.policies.activearena_groot.flow_dit import DiTConfig, FlowMatchingDiT

TINY = DiTConfig(
    action_dim=5,
    horizon=4,
    context_dim=12,
    width=16,
    depth=2,
    heads=2,
    queries=3,
    out_dim=20,
    decoder_width=24,
)


def _batch(b=3, s=6, seed=0):
    g = torch.Generator().manual_seed(seed)
    actions = torch.rand(b, TINY.horizon, TINY.action_dim, generator=g) * 2 - 1
    context = torch.randn(b, s, TINY.context_dim, generator=g)
    mask = torch.ones(b, s, dtype=torch.long)
    mask[0, 4:] = 0  # the first prompt is shorter: padding at its end
    return actions, context, mask


def test_the_paper_size_head_has_about_150m_parameters():
    with torch.device("meta"):
        head = FlowMatchingDiT(DiTConfig())
    c = head.config
    assert (c.depth, c.width, c.heads, c.queries, c.out_dim, c.decoder_width) == (16, 768, 12, 32, 1024, 1024)
    n = sum(p.numel() for p in head.parameters())
    assert 140e6 < n < 165e6, n
    cross = [b.cross for b in head.blocks]
    assert cross == [k % 2 == 0 for k in range(16)]  # even blocks cross-attend, odd ones self-attend


def test_shapes_and_the_time_distribution():
    head = FlowMatchingDiT(TINY).eval()
    actions, context, mask = _batch()
    t = torch.rand(3)
    assert head.velocity(actions, t, context, mask).shape == actions.shape
    assert head.sample(context, mask).shape == actions.shape
    times = head.sample_time(20000, torch.Generator().manual_seed(0))
    assert times.min() >= 0 and times.max() <= 1
    # Beta(1.5, 1) mapped to t = (s - b) / s: P(t < 0.5) = 1 - 0.5 ** 1.5 ~ 0.65, skewed to noise
    assert abs((times < 0.5).float().mean().item() - (1 - 0.5**1.5)) < 0.02
    assert head.loss(actions, context, mask, reduction="none").shape == (3,)


def test_padding_in_the_context_is_ignored():
    head = FlowMatchingDiT(TINY).eval()
    actions, context, mask = _batch()
    t = torch.full((3,), 0.3)
    v = head.velocity(actions, t, context, mask)
    changed = context.clone()
    changed[0, 4:] = 100.0  # only the masked-out positions of sample 0
    torch.testing.assert_close(head.velocity(actions, t, changed, mask), v)
    changed[0, 0] = 100.0  # a real token matters
    assert not torch.allclose(head.velocity(actions, t, changed, mask)[0], v[0])


def test_euler_sampling_runs_from_noise_at_t0_to_the_action_at_t1(monkeypatch):
    head = FlowMatchingDiT(TINY).eval()
    _, context, mask = _batch()
    target = torch.full((3, TINY.horizon, TINY.action_dim), 0.7)
    g = torch.Generator().manual_seed(5)
    noise = torch.randn(target.shape, generator=torch.Generator().manual_seed(5))
    seen = []

    def straight_line(x, t, ctx, m):  # the exact velocity of the line noise -> target
        seen.append(float(t[0]))
        return target - noise

    monkeypatch.setattr(head, "velocity", straight_line)
    out = head.sample(context, mask, generator=g)
    torch.testing.assert_close(out, target)
    assert seen == pytest.approx([0.0, 0.25, 0.5, 0.75])


def test_loss_falls_on_a_fixed_batch_and_a_seed_fixes_sampling():
    torch.manual_seed(0)
    head = FlowMatchingDiT(TINY)
    actions, context, mask = _batch()
    opt = torch.optim.AdamW(head.parameters(), lr=3e-3)
    g = torch.Generator().manual_seed(1)
    losses = []
    for _ in range(150):
        loss = head.loss(actions, context, mask, generator=g)
        opt.zero_grad()
        loss.backward()
        opt.step()
        losses.append(loss.item())
    first, last = sum(losses[:10]) / 10, sum(losses[-10:]) / 10
    assert last < 0.5 * first, (first, last)
    head.eval()
    a = head.sample(context, mask, generator=torch.Generator().manual_seed(7))
    b = head.sample(context, mask, generator=torch.Generator().manual_seed(7))
    c = head.sample(context, mask, generator=torch.Generator().manual_seed(8))
    torch.testing.assert_close(a, b)
    assert not torch.allclose(a, c)
    # trained, its samples land nearer the batch's chunks than noise does
    assert (a - actions).abs().mean() < (torch.randn_like(actions) - actions).abs().mean()


def test_bad_sizes_are_named():
    with pytest.raises(ValueError, match="multiple of heads"):
        DiTConfig(width=10, heads=3)
    with pytest.raises(ValueError, match="inference_steps"):
        DiTConfig(inference_steps=0)
