"""ActiveArena-VLA's FAST run (`fast_subtask_action_12_ws`). So far its action tokenizer
(``action_tokenizer``, fitted by ``activearena-fit-fast-tokenizer``); the ``activearena_fast``
policy type (the backbone's vocabulary extended with the action tokens) is not built yet."""
