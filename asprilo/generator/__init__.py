"""The instance generator: logic programs per scenario dimension and their multi-shot driver.

    from asprilo.generator import GeneratorConfig, generate
    config = GeneratorConfig.from_options({"-x": 11, "-y": 6, "-X": 4, "-Y": 2, "-H": True,
                                           "-p": 1, "-s": 16, "-P": 16, "-u": 16, "--prs": 1,
                                           "-r": 2, "-o": 2})
    for item in generate(config, count=3, seed=7):
        print(item.file_name(), item.instance.counts())

See asprilo/generator/README.md for the stages, the options and the YAML batch format.
"""

from .api import Generated, generate, generate_one, instance_seed, iter_generate, populate
from .config import GeneratorConfig, RunOptions
from .options import DEFAULT_SEED
from .pipeline import GenerationFailed
from .plan import GenerationPlan, make_plan
from .runs import generate_batch

__all__ = ["GeneratorConfig", "RunOptions", "Generated", "GenerationFailed", "GenerationPlan", "DEFAULT_SEED",
           "generate", "iter_generate", "generate_one", "populate", "make_plan", "instance_seed",
           "generate_batch"]
