<!DOCTYPE PickedPoints>
<PickedPoints>
 <DocumentData>
  <DataFileName name="man_flipped.obj"/>
 </DocumentData>
 <point x="0.002159" y="1.787181" z="0.045574" active="1" name="HEAD_TOP"/>
 <point x="0.083041" y="1.719396" z="0.000738" active="1" name="HEAD_LEFT_TEMPLE"/>
 <point x="0.004499" y="1.546032" z="0.085827" active="1" name="NECK_ADAM_APPLE"/>
 <point x="0.098279" y="0.008615" z="-0.066224" active="1" name="LEFT_HEEL"/>
 <point x="-0.109673" y="0.010216" z="-0.066697" active="1" name="RIGHT_HEEL"/>
 <point x="0.100352" y="1.323529" z="0.129165" active="1" name="LEFT_NIPPLE"/>
 <point x="-0.094945" y="1.321089" z="0.127256" active="1" name="RIGHT_NIPPLE"/>
 <point x="0.004277" y="1.513991" z="0.071000" active="1" name="SHOULDER_TOP"/>
 <point x="-0.002838" y="0.835270" z="0.128006" active="1" name="INSEAM_POINT"/>
 <point x="-0.005866" y="1.084570" z="0.168502" active="1" name="BELLY_BUTTON"/>
 <point x="-0.000707" y="1.068814" z="-0.081131" active="1" name="BACK_BELLY_BUTTON"/>
 <point x="-0.003278" y="0.823798" z="0.058632" active="1" name="CROTCH"/>
 <point x="-0.002762" y="0.880202" z="0.151784" active="1" name="PUBIC_BONE"/>
 <point x="-0.721317" y="1.419152" z="-0.046277" active="1" name="RIGHT_WRIST"/>
 <point x="0.719247" y="1.470217" z="-0.036338" active="1" name="LEFT_WRIST"/>
 <point x="-0.319086" y="1.386665" z="-0.024503" active="1" name="RIGHT_BICEP"/>
 <point x="-0.532468" y="1.395805" z="-0.035347" active="1" name="RIGHT_FOREARM"/>
 <point x="0.188557" y="1.503483" z="-0.019078" active="1" name="LEFT_SHOULDER"/>
 <point x="-0.185018" y="1.503037" z="-0.018407" active="1" name="RIGHT_SHOULDER"/>
 <point x="0.098730" y="0.841204" z="0.133044" active="1" name="LOW_LEFT_HIP"/>
 <point x="0.116982" y="0.650391" z="0.104840" active="1" name="LEFT_THIGH"/>
 <point x="0.098770" y="0.337571" z="0.031630" active="1" name="LEFT_CALF"/>
 <point x="0.105750" y="0.101073" z="0.017178" active="1" name="LEFT_ANKLE"/>
 <point x="0.466392" y="1.436025" z="-0.077001" active="1" name="LEFT_ELBOW"/>
 <point x="0.001010" y="0.924815" z="-0.120952" active="1" name="BUTTHOLE"/>
 <point x="-0.001671" y="1.537119" z="-0.054128" active="1" name="Cervicale"/>
 <point x="-0.171862" y="1.503111" z="-0.022700" active="1" name="Rt. Acromion"/>
 <point x="-0.437883" y="1.479378" z="-0.050443" active="1" name="Rt. Humeral Lateral Epicn"/>
 <point x="-0.723654" y="1.447345" z="-0.076897" active="1" name="Rt. Ulnar Styloid"/>
 <point x="0.918230" y="1.437017" z="-0.061287" active="1" name="LEFT_MIDDLE_FINGERTIP"/>
 <point x="0.899958" y="1.435162" z="-0.090773" active="1" name="LEFT_RING_FINGERTIP"/>
 <point x="0.907483" y="1.432707" z="-0.022406" active="1" name="LEFT_INDEX_FINGERTIP"/>
 <point x="0.861484" y="1.428964" z="-0.123613" active="1" name="LEFT_LITTLE_FINGERTIP"/>
 <point x="0.827915" y="1.426480" z="0.046164" active="1" name="LEFT_THUMB_TIP"/>
 <point x="-0.917859" y="1.440692" z="-0.060349" active="1" name="RIGHT_MIDDLE_FINGERTIP"/>
 <point x="-0.907828" y="1.435214" z="-0.022050" active="1" name="RIGHT_INDEX_FINGERTIP"/>
 <point x="-0.900222" y="1.438426" z="-0.092577" active="1" name="RIGHT_RING_FINGERTIP"/>
 <point x="-0.860573" y="1.431163" z="-0.123905" active="1" name="RIGHT_LITTLE_FINGERTIP"/>
 <point x="-0.826082" y="1.419337" z="0.043537" active="1" name="RIGHT_THUMB_TIP"/>
 <point x="0.069434" y="0.017641" z="0.177607" active="1" name="LEFT_BIG_TOE"/>
 <point x="-0.077568" y="0.013885" z="0.177842" active="1" name="RIGHT_BIG_TOE"/>
</PickedPoints>
