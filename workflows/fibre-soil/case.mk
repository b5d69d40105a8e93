# Fibre-reinforced soil: triaxial compression with 0 %, 0.5 % and 1 % of fibres, on a loose and a
# dense sample from one fill (workflows/fibre-soil/README.md).
#   make -f Makefile.cases fibre-soil           fill 2,000 spheres; consolidate them to 100 kPa twice
#                                               (loose: with the scene's friction; dense: frictionless);
#                                               shear each sample three times to 15 % axial strain and
#                                               report; the rate check: each sample's unreinforced
#                                               shear again at half the platen speed
#   make -f Makefile.cases fibre-soil-scatter   the dense sample from four fills (seeds 11-14), each
#                                               sheared without and with 1 % of fibres: how strength
#                                               and gain spread with the packing
FS_DIR := $(OUT)/fibre-soil
FS_SCENE := workflows/fibre-soil/scene.toml
FS_VARIANT := workflows/fibre-soil/scene_variant.sh
FS_STAGES := shear_0 shear_05 shear_1
FS_REPORT := $(PYTHON) scripts/triaxial_report.py
# The fibres' cross-section pi d^2 / 4 for d = 0.3 mm (the scene's diameter): mean fibre stress.
FS_AREA := 7.0686e-8
FS_SCATTER_SEEDS := 12 13 14

# The scene's variants (scene_variant.sh): dense (frictionless spheres: the dense sample's
# consolidation), half (the platens at half speed: the rate check), fill-N (the fill's seed N).
$(FS_DIR)/scenes/dense.toml $(FS_DIR)/scenes/half.toml: $(FS_DIR)/scenes/%.toml: $(FS_SCENE) $(FS_VARIANT)
	@mkdir -p $(@D)
	bash $(FS_VARIANT) $(FS_SCENE) $* > $@.tmp && mv $@.tmp $@
$(FS_DIR)/scenes/fill-%.toml: $(FS_SCENE) $(FS_VARIANT)
	@mkdir -p $(@D)
	bash $(FS_VARIANT) $(FS_SCENE) seed=$* > $@.tmp && mv $@.tmp $@

# The fill (seed 11, the scene's) and its two samples, both sheared with the scene itself: loose,
# consolidated with the scene's friction (30 deg); dense, consolidated frictionless.
$(FS_DIR)/fill/filled.h5: $(FS_SCENE) $(BIN)/gen-primary
	@mkdir -p $(@D)
	$(BIN)/gen-primary --scene $< --out $@
$(FS_DIR)/loose/consolidated.h5: $(FS_SCENE) $(FS_DIR)/fill/filled.h5 $(BIN)/compact
	@mkdir -p $(@D)
	$(BIN)/compact --scene $< --in $(FS_DIR)/fill/filled.h5 --out $@
$(FS_DIR)/dense/consolidated.h5: $(FS_DIR)/scenes/dense.toml $(FS_DIR)/fill/filled.h5 $(BIN)/compact
	@mkdir -p $(@D)
	$(BIN)/compact --scene $< --in $(FS_DIR)/fill/filled.h5 --out $@

# One shear: fs_shear(OUT prefix, STAGE, SCENE, IN checkpoint, more run-stage options); the wall
# log every 200 steps (forces and positions of the six faces).
define fs_shear
$(1).h5 $(1).walls.csv &: $(3) $(4) $(BIN)/run-stage
	@mkdir -p $$(@D)
	$(BIN)/run-stage --scene $(3) --stage $(2) --in $(4) --out $(1).h5 --wall-forces $(1).walls.csv --wall-forces-every 200 $(5)
endef

# Each sample in DIR: its three shears from the same consolidated state (VTK frames of particles
# and fibres every 1.5 % of axial strain) and their report; the coarse-grained stress of the 1 %
# sample at the end, fibres included (docs/post.md; a 3 mm grid); the rate check, its unreinforced
# shear at half the platen speed (half/shear_0).
define fs_case
$(foreach s,$(FS_STAGES),$(eval $(call fs_shear,$(1)/$(s),$(s),$(FS_SCENE),$(1)/consolidated.h5,--vtk $(1)/vtk)))
$(eval $(call fs_shear,$(1)/half/shear_0,shear_0,$(FS_DIR)/scenes/half.toml,$(1)/consolidated.h5))
$(1)/summary.csv $(1)/curves.png $(1)/curves.csv $(1)/gain.png $(1)/fibre_tension.png &: \
    $(foreach s,$(FS_STAGES),$(1)/$(s).walls.csv) scripts/triaxial_report.py scripts/post_table.py
	$(FS_REPORT) --run "0 %:0:$(1)/shear_0.walls.csv" --run "0.5 %:0.005:$(1)/shear_05.walls.csv:$(1)/vtk/shear_05_fibres.pvd" \
	  --run "1 %:0.01:$(1)/shear_1.walls.csv:$(1)/vtk/shear_1_fibres.pvd" --fibre-area $(FS_AREA) \
	  --summary $(1)/summary.csv --curves $(1)/curves.png --curves-csv $(1)/curves.csv \
	  --gain $(1)/gain.png --fibres $(1)/fibre_tension.png
$(1)/fields_1.vti: $(1)/shear_1.h5 $(BIN)/post-macro
	$(BIN)/post-macro --in $(1)/shear_1.h5 --grid $$@ --cell 0.003 --width 0.003 --average-csv $(1)/average_1.csv
$(1)/rate.csv $(1)/rate.png &: $(1)/shear_0.walls.csv $(1)/half/shear_0.walls.csv scripts/triaxial_report.py
	$(FS_REPORT) --run "platens 15 mm/s:0:$(1)/shear_0.walls.csv" --run "7.5 mm/s:0:$(1)/half/shear_0.walls.csv" \
	  --summary $(1)/rate.csv --curves $(1)/rate.png
endef
$(foreach d,loose dense,$(eval $(call fs_case,$(FS_DIR)/$(d))))

# The scatter: the dense sample of each further fill, without and with 1 % of fibres (the same
# fibre seed), beside the case's own (seed 11, dense/).
define fs_scatter_fill
$(FS_DIR)/scatter/$(1)/filled.h5: $(FS_DIR)/scenes/fill-$(1).toml $(BIN)/gen-primary
	@mkdir -p $$(@D)
	$(BIN)/gen-primary --scene $$< --out $$@
$(FS_DIR)/scatter/$(1)/consolidated.h5: $(FS_DIR)/scenes/dense.toml $(FS_DIR)/scatter/$(1)/filled.h5 $(BIN)/compact
	$(BIN)/compact --scene $$< --in $(FS_DIR)/scatter/$(1)/filled.h5 --out $$@
$(foreach s,shear_0 shear_1,$(eval $(call fs_shear,$(FS_DIR)/scatter/$(1)/$(s),$(s),$(FS_SCENE),$(FS_DIR)/scatter/$(1)/consolidated.h5)))
endef
$(foreach n,$(FS_SCATTER_SEEDS),$(eval $(call fs_scatter_fill,$(n))))
fs_scatter_walls = $(FS_DIR)/dense/shear_0.walls.csv $(FS_DIR)/dense/shear_1.walls.csv \
  $(foreach n,$(FS_SCATTER_SEEDS),$(FS_DIR)/scatter/$(n)/shear_0.walls.csv $(FS_DIR)/scatter/$(n)/shear_1.walls.csv)
$(FS_DIR)/scatter/scatter.csv $(FS_DIR)/scatter/scatter.png &: $(fs_scatter_walls) scripts/triaxial_report.py scripts/triaxial_scatter.py
	$(PYTHON) scripts/triaxial_scatter.py --fibre-fraction 0.01 --fill "11:$(FS_DIR)/dense/shear_0.walls.csv:$(FS_DIR)/dense/shear_1.walls.csv" \
	  $(foreach n,$(FS_SCATTER_SEEDS),--fill "$(n):$(FS_DIR)/scatter/$(n)/shear_0.walls.csv:$(FS_DIR)/scatter/$(n)/shear_1.walls.csv") \
	  --table $(FS_DIR)/scatter/scatter.csv --png $(FS_DIR)/scatter/scatter.png

.PHONY: fibre-soil fibre-soil-outputs fibre-soil-scatter fibre-soil-scatter-outputs
fibre-soil: build
	@$(MAKE) --no-print-directory -f $(SELF) fibre-soil-outputs
	@echo "fibre-soil: $(FS_DIR)/loose/ and dense/: summary.csv, curves.png/.csv, gain.png, fibre_tension.png, fields_1.vti, rate.csv/.png"
fibre-soil-outputs: $(foreach d,loose dense,$(FS_DIR)/$(d)/summary.csv $(FS_DIR)/$(d)/fields_1.vti $(FS_DIR)/$(d)/rate.csv)
fibre-soil-scatter: build
	@$(MAKE) --no-print-directory -f $(SELF) fibre-soil-scatter-outputs
	@echo "fibre-soil-scatter: $(FS_DIR)/scatter/scatter.csv, scatter.png"
fibre-soil-scatter-outputs: $(FS_DIR)/scatter/scatter.csv
CASES += fibre-soil
