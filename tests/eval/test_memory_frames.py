"""activearena-memory-frames: what a memory-aware policy held in memory when it decided."""

from pathlib import Path

from lerobot_activearena.eval.memory_frames import (
    decision_memory,
    decision_step,
    draw_memory,
    play_and_record,
)


def test_memory_frames_draws_the_bank_at_the_last_decision(tmp_path):
    """activearena-memory-frames' parts on a saved tiny chunk-memory checkpoint (K = 2): the bank holds
    the chunk boundaries before each step, and the picture has one panel per memory frame."""
    saved = Path(__file__).resolve().parents[1] / "policies" / "fixtures" / "oft_saved_2026_11_25"
    played = play_and_record(
        saved / "checkpoint",
        "click_bell_rotate_view",
        "id",
        0,
        str(saved / "tiny_qwen3_vl"),
        episode_length=40,
    )
    assert len(played["banks"]) == 40 and len(played["frames"]) == 41  # reset + one per step
    assert played["banks"][15] == [0] and played["banks"][39] == [16, 32]  # K = 2 newest chunk frames
    assert decision_step(40, played["chunk"]) == 32 and played["record"]["steps"] == 40
    assert decision_memory(played) == (32, [0, 16])
    assert played["frames"][0].shape == (96, 128, 3)
    out = draw_memory(played, "bell", tmp_path / "memory.png")
    assert out.stat().st_size > 1000


def test_a_chunk_memory_re_planning_every_8_steps_is_drawn_with_the_frames_its_decision_read():
    """Re-planning every 8 steps the bank also holds frames 8, 24, ...; the decision at step 40 read
    only those 16 and 32 steps back (K = 2)."""
    banks = [list(range(0, t + 1, 8))[-4:] for t in range(47)]
    played = {"banks": banks, "chunk": 8, "read_stride": 16, "history": 2}
    assert decision_memory(played) == (40, [8, 24])
    assert decision_memory({**played, "read_stride": None}) == (40, [8, 16, 24, 32])  # a keyframe memory
