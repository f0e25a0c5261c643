"""The reproduction of Buczkowski & Kleiber (2009) — not the library: what the workflow
computes for each figure (:mod:`.scenes`), the paper's prose claims as numerical criteria
(:mod:`.claims`), checks against printed values and the verdict gate (:mod:`.verify`), the
reports (:mod:`.report`) and the figures (:mod:`.plots`)."""
